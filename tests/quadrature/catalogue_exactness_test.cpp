// Every deterministic rule of the registry integrates tensor polynomials on [0,1]^4 exactly
// up to its declared degree, and not at the next one (declaring too little fails as well as
// too much), as quadpy's scheme tests do.
//
// The integrands are the products phi_i(s) phi_j(t) phi_k(u) phi_l(v) of shifted Legendre
// polynomials with i + j + k + l = D: they span the polynomials of total degree D modulo lower
// degrees, and their exact integral over the cube is 1 for i = j = k = l = 0 and 0 otherwise
// (orthonormality).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "kernel/legendre_basis.h"
#include "quadrature/registry.h"

namespace radquad {
namespace {

constexpr int kMaxOrder = 12;

// The rule's points on [0,1]^4, product rules expanded.
LinkSamples expandedPoints(const Rule& rule) {
  const RuleSamples samples = rule.samples(0);
  if (!samples.isProduct) return samples.points;
  LinkSamples points;
  for (std::size_t i = 0; i < samples.receiver.size(); ++i) {
    for (std::size_t j = 0; j < samples.source.size(); ++j) {
      points.push(samples.receiver.u[i], samples.receiver.v[i], samples.source.u[j],
                  samples.source.v[j], samples.receiver.weight[i] * samples.source.weight[j]);
    }
  }
  return points;
}

// max over i+j+k+l = degree of |rule(phi_i phi_j phi_k phi_l) - exact|.
double worstError(const LinkSamples& points, int degree) {
  double worst = 0.0;
  std::array<double, kMaxOrder + 1> ps, pt, pu, pv;
  for (int i = 0; i <= degree; ++i) {
    for (int j = 0; i + j <= degree; ++j) {
      for (int k = 0; i + j + k <= degree; ++k) {
        const int l = degree - i - j - k;
        double sum = 0.0;
        for (std::size_t q = 0; q < points.size(); ++q) {
          shiftedLegendreValues(degree, points.s[q], ps.data());
          shiftedLegendreValues(degree, points.t[q], pt.data());
          shiftedLegendreValues(degree, points.u[q], pu.data());
          shiftedLegendreValues(degree, points.v[q], pv.data());
          sum += points.weight[q] * ps[i] * pt[j] * pu[k] * pv[l];
        }
        const double exact = degree == 0 ? 1.0 : 0.0;
        worst = std::max(worst, std::fabs(sum - exact));
      }
    }
  }
  return worst;
}

std::vector<std::string> deterministicRuleNames() {
  std::vector<std::string> names;
  for (const auto& rule : namedRules()) {
    if (!rule->isRandom()) names.push_back(rule->name());
  }
  // Parametrised forms with unequal axes: the degree is set by the poorest axis.
  names.push_back("Gauss:2x3x4x5");
  names.push_back("Gauss:5x4x3x4");
  return names;
}

class CatalogueExactness : public testing::TestWithParam<std::string> {};

TEST_P(CatalogueExactness, ExactToExactlyTheDeclaredDegree) {
  const auto rule = findRule(GetParam());
  ASSERT_TRUE(rule->degree().has_value()) << rule->toString();
  const int declared = *rule->degree();
  ASSERT_LT(declared + 1, kMaxOrder);
  const LinkSamples points = expandedPoints(*rule);
  ASSERT_EQ(points.size(), rule->sampleCount()) << rule->toString();
  for (int degree = 0; degree <= declared; ++degree) {
    EXPECT_LT(worstError(points, degree), 1e-11)
        << rule->toString() << " is not exact at degree " << degree;
  }
  EXPECT_GT(worstError(points, declared + 1), 1e-6)
      << rule->toString() << " is also exact at degree " << declared + 1
      << ": its declared degree is too low";
}

INSTANTIATE_TEST_SUITE_P(Registry, CatalogueExactness, testing::ValuesIn(deterministicRuleNames()),
                         [](const testing::TestParamInfo<std::string>& info) {
                           std::string name = info.param;
                           for (char& c : name) {
                             if (c == ':') c = '_';
                           }
                           return name;
                         });

// The random rules declare no degree, and every named rule is either random or declares one.
TEST(CatalogueExactness, RandomRulesDeclareNoDegree) {
  for (const auto& rule : namedRules()) {
    EXPECT_EQ(rule->isRandom(), !rule->degree().has_value()) << rule->toString();
  }
}

}  // namespace
}  // namespace radquad
