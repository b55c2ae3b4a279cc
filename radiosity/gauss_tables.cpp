#include "radiosity/gauss_tables.h"
#include "kernel/input_error.h"


#include "quadrature/gauss_legendre.h"

namespace radquad {

GaussTables::GaussTables(int degree) {
  sides_.resize(kMaxPointsPerAxis * kMaxPointsPerAxis);
  for (int nu = 1; nu <= kMaxPointsPerAxis; ++nu) {
    for (int nv = 1; nv <= kMaxPointsPerAxis; ++nv) {
      GaussSide& side = sides_[std::size_t((nu - 1) * kMaxPointsPerAxis + (nv - 1))];
      const GaussLegendreRule& gu = gaussLegendreUnit(nu);
      const GaussLegendreRule& gv = gaussLegendreUnit(nv);
      for (int i = 0; i < nu; ++i) {
        for (int j = 0; j < nv; ++j) {
          side.samples.push(gu.nodes[std::size_t(i)], gv.nodes[std::size_t(j)],
                            gu.weights[std::size_t(i)] * gv.weights[std::size_t(j)]);
        }
      }
      side.basis = makeWeightedBasisTable(side.samples, degree);
    }
  }
}

const GaussSide& GaussTables::side(int pointsU, int pointsV) const {
  RADQUAD_REQUIRE(pointsU >= 1 && pointsU <= kMaxPointsPerAxis);
  RADQUAD_REQUIRE(pointsV >= 1 && pointsV <= kMaxPointsPerAxis);
  return sides_[std::size_t((pointsU - 1) * kMaxPointsPerAxis + (pointsV - 1))];
}

}  // namespace radquad
