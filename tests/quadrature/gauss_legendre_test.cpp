// Gauss-Legendre nodes and weights against published tables and exactness degrees.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "kernel/input_error.h"
#include "quadrature/gauss_legendre.h"
#include "tests/quadrature/legendre_reference.h"

namespace radquad {
namespace {

using testing::legendreAt;

TEST(GaussLegendre, ThreeAndFivePointClosedForms) {
  const auto three = gaussLegendre(3);
  EXPECT_NEAR(three.nodes[2], std::sqrt(3.0 / 5.0), 1e-16);
  EXPECT_NEAR(three.weights[2], 5.0 / 9.0, 1e-16);
  EXPECT_NEAR(three.weights[1], 8.0 / 9.0, 1e-16);
  const auto five = gaussLegendre(5);
  EXPECT_NEAR(five.nodes[3], std::sqrt(5 - 2 * std::sqrt(10.0 / 7)) / 3, 1e-16);
  EXPECT_NEAR(five.nodes[4], std::sqrt(5 + 2 * std::sqrt(10.0 / 7)) / 3, 1e-16);
  EXPECT_NEAR(five.weights[2], 128.0 / 225.0, 1e-16);
  EXPECT_NEAR(five.weights[3], (322 + 13 * std::sqrt(70.0)) / 900, 1e-16);
  EXPECT_NEAR(five.weights[4], (322 - 13 * std::sqrt(70.0)) / 900, 1e-16);
}

TEST(GaussLegendre, TwentyPointsMatchAbramowitzStegunTable) {
  // Abramowitz and Stegun 1964, table 25.4, n = 20: the innermost and outermost pairs.
  const auto rule = gaussLegendre(20);
  EXPECT_NEAR(rule.nodes[10], 0.076526521133497333755, 1e-15);
  EXPECT_NEAR(rule.weights[10], 0.152753387130725850698, 1e-15);
  EXPECT_NEAR(rule.nodes[19], 0.993128599185094924786, 1e-15);
  EXPECT_NEAR(rule.weights[19], 0.017614007139152118312, 1e-15);
}

// An n-point rule on [0,1] integrates polynomials of degree 2n-1 exactly and not degree 2n.
// Probed with the orthonormal shifted Legendre polynomials: int phi_a phi_b = delta_ab for
// a + b <= 2n - 1, while phi_n^2 (degree 2n, integral 1) vanishes at every node, so the rule
// gives 0: a well-conditioned witness of non-exactness at any n.
TEST(GaussLegendre, ExactToDegreeTwoNMinusOneOnly) {
  for (int n = 1; n <= 24; ++n) {
    const auto& rule = gaussLegendreUnit(n);
    for (int a = 0; a <= n; ++a) {
      for (int b = 0; a + b <= 2 * n - 1 && b <= n; ++b) {
        double sum = 0.0;
        for (int i = 0; i < n; ++i)
          sum += rule.weights[i] * legendreAt(a, rule.nodes[i]) * legendreAt(b, rule.nodes[i]);
        EXPECT_NEAR(sum, a == b ? 1.0 : 0.0, 1e-13) << "n = " << n << ", phi_" << a << " phi_" << b;
      }
    }
    double square = 0.0;
    for (int i = 0; i < n; ++i)
      square += rule.weights[i] * std::pow(legendreAt(n, rule.nodes[i]), 2);
    EXPECT_LT(square, 1e-20) << "n = " << n;  // exact value 1
  }
}

TEST(GaussLegendre, PointCountOutOfRangeIsAnInputError) {
  EXPECT_THROW(gaussLegendre(0), InputError);
  EXPECT_THROW(gaussLegendreUnit(kMaxGaussPoints + 1), InputError);
}

}  // namespace
}  // namespace radquad
