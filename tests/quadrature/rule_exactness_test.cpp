// One parametrised test over the registry: every deterministic rule integrates every tensor
// Legendre polynomial phi_a(s) phi_b(t) phi_c(u) phi_e(v) on [0,1]^4 of total degree
// a+b+c+e <= its declared degree exactly (integral 1 for the constant, 0 otherwise), and
// fails on at least one of the next degree, so that declaring too little fails as well as
// too much (as quadpy's scheme tests do). These polynomials span all polynomials of that
// total degree and, being orthonormal, keep the test well conditioned at high degree.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <vector>

#include "quadrature/rule.h"
#include "quadrature/registry.h"
#include "tests/quadrature/legendre_reference.h"

namespace radquad {
namespace {

using testing::legendreAt;

std::vector<std::string> deterministicRuleNames() {
  std::vector<std::string> names;
  for (const auto& rule : namedRules()) {
    if (!rule->isRandom()) names.push_back(rule->name());
  }
  // Parametrised forms with unequal axes, so the degree is the minimum over the axes.
  for (const char* name : {"Gauss:1x2x3x4", "Gauss:4x4x2x5", "Gauss:5x5x5x5"})
    names.push_back(name);
  return names;
}

// Largest error over the tensor Legendre polynomials of total degree exactly `degree`.
double worstPolynomialError(const LinkSamples& points, int degree) {
  double worst = 0.0;
  for (int a = 0; a <= degree; ++a) {
    for (int b = 0; a + b <= degree; ++b) {
      for (int c = 0; a + b + c <= degree; ++c) {
        const int e = degree - a - b - c;
        double sum = 0.0;
        for (std::size_t k = 0; k < points.size(); ++k) {
          sum += points.weight[k] * legendreAt(a, points.s[k]) * legendreAt(b, points.t[k]) *
                 legendreAt(c, points.u[k]) * legendreAt(e, points.v[k]);
        }
        worst = std::max(worst, std::fabs(sum - (degree == 0 ? 1.0 : 0.0)));
      }
    }
  }
  return worst;
}

class RuleExactness : public ::testing::TestWithParam<std::string> {};

TEST_P(RuleExactness, ExactToExactlyTheDeclaredDegree) {
  const auto rule = findRule(GetParam());
  ASSERT_TRUE(rule->degree().has_value()) << rule->toString();
  const int declared = *rule->degree();
  const LinkSamples points = flattenedPoints(rule->samples(0));
  ASSERT_EQ(points.size(), rule->sampleCount()) << rule->toString();
  double weightSum = 0.0;
  for (double w : points.weight) weightSum += w;
  EXPECT_NEAR(weightSum, 1.0, 1e-14) << rule->toString();
  for (int degree = 0; degree <= declared; ++degree) {
    EXPECT_LT(worstPolynomialError(points, degree), 1e-12)
        << rule->toString() << " is not exact at total degree " << degree;
  }
  EXPECT_GT(worstPolynomialError(points, declared + 1), 1e-9)
      << rule->toString() << " is also exact at degree " << declared + 1
      << ": its declared degree is too low";
}

INSTANTIATE_TEST_SUITE_P(Registry, RuleExactness, ::testing::ValuesIn(deterministicRuleNames()),
                         [](const ::testing::TestParamInfo<std::string>& info) {
                           std::string name = info.param;
                           for (char& c : name) {
                             if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
                           }
                           return name;
                         });

}  // namespace
}  // namespace radquad
