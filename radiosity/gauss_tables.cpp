#include "radiosity/gauss_tables.h"

#include "kernel/input_error.h"
#include "quadrature/gauss_legendre.h"

namespace radquad {

GaussTables::GaussTables(int degree) {
  sides_.resize(kMaxPointsPerAxis * kMaxPointsPerAxis);
  for (int nu = 1; nu <= kMaxPointsPerAxis; ++nu) {
    for (int nv = 1; nv <= kMaxPointsPerAxis; ++nv) {
      GaussSide& side = sides_[std::size_t((nu - 1) * kMaxPointsPerAxis + (nv - 1))];
      side.samples = gaussProductSamples(nu, nv);
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
