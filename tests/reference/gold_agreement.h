// What the exact gold's tests share: two golds of one link agree within their summed error
// estimates, entry by entry; the outline of the shadows' union closes up; and the scene of two
// overlapping tilted blockers between the unit squares z = 0 (receiver) and z = 1 (source),
// whose shadows need a polygon union.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "kernel/occluder_scene.h"
#include "kernel/patch.h"
#include "reference/exact_gold.h"
#include "reference/exact_visibility.h"

namespace radquad {

// |a - b| <= a's error + b's error (+ slack) for every entry of K; `what` names the case.
inline void expectWithinSummedErrors(const ExactGold& a, const ExactGold& b,
                                     const std::string& what, double slack = 0.0) {
  ASSERT_EQ(a.coupling.rows(), b.coupling.rows()) << what;
  for (Eigen::Index i = 0; i < a.coupling.rows(); ++i) {
    for (Eigen::Index j = 0; j < a.coupling.cols(); ++j) {
      EXPECT_LE(std::fabs(a.coupling(i, j) - b.coupling(i, j)),
                a.couplingError(i, j) + b.couplingError(i, j) + slack)
          << what << " K[" << i << "][" << j << "]";
    }
  }
}

// The outline's pieces close up to the bit: every end is some piece's start, as many times.
// (A gap of rounding's size shows at degree 2 as 1e-11 of the form factor where the foot of x
// lies far outside the source: each piece's term is a triangle from the foot.)
inline void expectPiecesCloseUp(const VisibleRings& visible, const std::string& what) {
  std::vector<std::pair<double, double>> starts, ends;
  for (std::size_t s = 0; s < visible.segmentCount(); ++s) {
    starts.push_back({visible.segmentStart(s).x(), visible.segmentStart(s).y()});
    ends.push_back({visible.segmentEnd(s).x(), visible.segmentEnd(s).y()});
  }
  std::sort(starts.begin(), starts.end());
  std::sort(ends.begin(), ends.end());
  EXPECT_EQ(starts, ends) << what;
}

// Adds the two blockers to `scene` (not committed).
inline void addTwoTiltedBlockers(OccluderScene& scene) {
  scene.addParallelogram(Patch::make({0.1, 0.1, 0.4}, {0.5, 0.1, 0.05}, {0.05, 0.5, 0}, "a"));
  scene.addParallelogram(Patch::make({0.3, 0.2, 0.6}, {0.4, -0.1, 0}, {0.1, 0.6, 0.1}, "b"));
}

}  // namespace radquad
