// Stroud Cn 5-7 and the hierarchical Cn 3-1: the facts of docs/design.md, "The kernel and the rules".
#include <gtest/gtest.h>

#include <cmath>
#include <numeric>

#include "quadrature/registry.h"

namespace radquad {
namespace {

TEST(Stroud65, SixtyFivePointsInTheCubeWithWeightsSummingToOne) {
  const auto rule = findRule("Stroud65");
  const RuleSamples samples = rule->samples(0);
  ASSERT_FALSE(samples.isProduct);
  const LinkSamples& p = samples.points;
  ASSERT_EQ(p.size(), 65u);
  EXPECT_NEAR(std::accumulate(p.weight.begin(), p.weight.end(), 0.0), 1.0, 4e-15);
  for (std::size_t k = 0; k < p.size(); ++k) {
    for (double x : {p.s[k], p.t[k], p.u[k], p.v[k]}) {
      EXPECT_GT(x, 0.0);
      EXPECT_LT(x, 1.0);
    }
    EXPECT_GT(p.weight[k], 0.0);
  }
  // Centre weight 4/(5n+4) = 1/6 for n = 4; the 64 others 5/((5n+4) 2^n) = 5/384.
  EXPECT_DOUBLE_EQ(p.weight[0], 1.0 / 6.0);
  for (std::size_t k = 1; k < p.size(); ++k) EXPECT_DOUBLE_EQ(p.weight[k], 5.0 / 384.0);
}

TEST(HierStroud, EightEqualPointsInEachReceiverQuadrant) {
  const auto rule = findRule("HierStroud");
  const LinkSamples p = rule->samples(0).points;
  ASSERT_EQ(p.size(), 32u);
  int perQuadrant[2][2] = {{0, 0}, {0, 0}};
  for (std::size_t k = 0; k < p.size(); ++k) {
    EXPECT_DOUBLE_EQ(p.weight[k], 1.0 / 32.0);
    ASSERT_TRUE(p.s[k] != 0.5 && p.t[k] != 0.5);
    ++perQuadrant[p.s[k] > 0.5][p.t[k] > 0.5];
    // Cn 3-1 points lie on the sphere of radius sqrt(n/3) in [-1,1]^n coordinates: each of
    // the n/2 coordinate pairs has squared length 2/3.
    const double x1 = 4.0 * std::fmod(p.s[k], 0.5) - 1.0, x2 = 4.0 * std::fmod(p.t[k], 0.5) - 1.0;
    const double x3 = 2.0 * p.u[k] - 1.0, x4 = 2.0 * p.v[k] - 1.0;
    EXPECT_NEAR(x1 * x1 + x2 * x2 + x3 * x3 + x4 * x4, 4.0 / 3.0, 1e-12);
  }
  for (auto& row : perQuadrant) {
    for (int count : row) EXPECT_EQ(count, 8);
  }
}

}  // namespace
}  // namespace radquad
