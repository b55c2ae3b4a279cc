// The two halves of Gauss-Legendre product rules on an element's parameter square,
// n_u x n_v points (quadrature's gaussProductSamples, the Gauss rules' own point sets), with
// their weighted basis tables for one degree, built once for every n_u, n_v in
// 1..kMaxPointsPerAxis. A link's rule {Rs, Rt, Su, Sv} uses side(Rs, Rt) on the receiver and
// side(Su, Sv) on the source.
#pragma once

#include <vector>

#include "kernel/coupling.h"
#include "kernel/sample_points.h"

namespace radquad {

struct GaussSide {
  PatchSamples samples;
  WeightedBasisTable basis;
};

class GaussTables {
 public:
  static constexpr int kMaxPointsPerAxis = 8;

  explicit GaussTables(int degree);

  // 1 <= pointsU, pointsV <= kMaxPointsPerAxis.
  const GaussSide& side(int pointsU, int pointsV) const;

 private:
  std::vector<GaussSide> sides_;
};

}  // namespace radquad
