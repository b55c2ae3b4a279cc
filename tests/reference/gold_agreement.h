// What the exact gold's tests share: two golds of one link agree within their summed error
// estimates, entry by entry; and the scene of two overlapping tilted blockers between the unit
// squares z = 0 (receiver) and z = 1 (source), whose shadows need a polygon union.
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "kernel/occluder_scene.h"
#include "kernel/patch.h"
#include "reference/exact_gold.h"

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

// Adds the two blockers to `scene` (not committed).
inline void addTwoTiltedBlockers(OccluderScene& scene) {
  scene.addParallelogram(Patch::make({0.1, 0.1, 0.4}, {0.5, 0.1, 0.05}, {0.05, 0.5, 0}, "a"));
  scene.addParallelogram(Patch::make({0.3, 0.2, 0.6}, {0.4, -0.1, 0}, {0.1, 0.6, 0.1}, "b"));
}

}  // namespace radquad
