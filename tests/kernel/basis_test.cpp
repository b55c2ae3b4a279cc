// The orthonormal shifted Legendre basis of docs/design.md.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "kernel/input_error.h"
#include "kernel/legendre_basis.h"
#include "quadrature/gauss_legendre.h"

namespace radquad {
namespace {

TEST(LegendreBasis, MatchesClosedForms) {
  // P_2(x) = (3x^2 - 1)/2, P_3(x) = (5x^3 - 3x)/2 at x = 2t - 1.
  for (double t : {0.0, 0.13, 0.5, 0.77, 1.0}) {
    double values[4];
    shiftedLegendreValues(3, t, values);
    const double x = 2 * t - 1;
    EXPECT_DOUBLE_EQ(values[0], 1.0);
    EXPECT_NEAR(values[1], std::sqrt(3.0) * x, 1e-15);
    EXPECT_NEAR(values[2], std::sqrt(5.0) * (3 * x * x - 1) / 2, 1e-14);
    EXPECT_NEAR(values[3], std::sqrt(7.0) * (5 * x * x * x - 3 * x) / 2, 1e-14);
  }
}

// int_[0,1]^2 phi_a phi_b = delta_ab for every degree 0..8, by a 10x10 Gauss rule (exact for
// the degree-16 products along each axis).
TEST(LegendreBasis, TensorBasisIsOrthonormal) {
  const GaussLegendreRule& gauss = gaussLegendreUnit(10);
  for (int degree = 0; degree <= kMaxBasisDegree; ++degree) {
    const int n = basisFunctionCount(degree);
    std::vector<double> gram(n * n, 0.0), values(n);
    for (int i = 0; i < 10; ++i) {
      for (int j = 0; j < 10; ++j) {
        tensorBasisValues(degree, gauss.nodes[i], gauss.nodes[j], values.data());
        const double w = gauss.weights[i] * gauss.weights[j];
        for (int a = 0; a < n; ++a) {
          for (int b = 0; b < n; ++b) gram[a * n + b] += w * values[a] * values[b];
        }
      }
    }
    for (int a = 0; a < n; ++a) {
      for (int b = 0; b < n; ++b) {
        EXPECT_NEAR(gram[a * n + b], a == b ? 1.0 : 0.0, 1e-13)
            << "degree " << degree << " pair " << a << "," << b;
      }
    }
  }
}

TEST(LegendreBasis, IndexRunsAlongEdgeUFirst) {
  // a = i*(d+1) + j with i along u: function 1 of degree 1 is phi_0(u) phi_1(v).
  double values[4];
  tensorBasisValues(1, 0.9, 0.2, values);
  EXPECT_NEAR(values[1], std::sqrt(3.0) * (2 * 0.2 - 1), 1e-15);
  EXPECT_NEAR(values[2], std::sqrt(3.0) * (2 * 0.9 - 1), 1e-15);
}

TEST(LegendreBasis, AbsoluteIntegralsMatchClosedForms) {
  EXPECT_DOUBLE_EQ(legendreAbsoluteIntegral(0), 1.0);
  EXPECT_NEAR(legendreAbsoluteIntegral(1), std::sqrt(3.0) / 2, 1e-14);
  // phi_2 changes sign at t = 1/2 +- 1/(2 sqrt 3): int |phi_2| = 2 sqrt(5) / (3 sqrt(3)).
  EXPECT_NEAR(legendreAbsoluteIntegral(2), 2 * std::sqrt(5.0) / (3 * std::sqrt(3.0)), 1e-12);
}

TEST(LegendreBasis, DegreeOutOfRangeIsAnInputError) {
  EXPECT_THROW(validateBasisDegree(-1), InputError);
  EXPECT_THROW(validateBasisDegree(9), InputError);
  EXPECT_NO_THROW(validateBasisDegree(8));
}

}  // namespace
}  // namespace radquad
