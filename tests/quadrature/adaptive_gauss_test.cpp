// The adaptive Gauss rule choice of Gershbein 1995, Figure 4: the choices follow from the
// figure's pseudocode and the text of section 5 (the 9-instead-of-81 example).
#include <gtest/gtest.h>

#include <array>
#include <vector>

#include "quadrature/adaptive_gauss.h"
#include "quadrature/random/philox.h"

namespace radquad {
namespace {

AdaptiveGaussInput input(int degree, const std::vector<double>& magnitudes, double threshold,
                         bool partial = false) {
  AdaptiveGaussInput in;
  in.degree = degree;
  in.magnitudes = magnitudes.data();
  in.errThres = threshold;
  in.partiallyOccluded = partial;
  return in;
}

// (d+1)^2 zeros with the given (i, j) entries set.
std::vector<double> coefficients(int degree, std::vector<std::array<int, 2>> nonzero,
                                 double value = 1.0) {
  std::vector<double> out(std::size_t((degree + 1) * (degree + 1)), 0.0);
  for (const auto& [i, j] : nonzero) out[std::size_t(i * (degree + 1) + j)] = value;
  return out;
}

TEST(AdaptiveGauss, ReportExampleQuadraticConstantSource) {
  // Section 5: a quadratic basis whose source has only its constant function significant
  // needs 3x3 receiver points and 1x1 source points: 9 kernel evaluations instead of 81.
  const auto magnitudes = coefficients(2, {{0, 0}});
  const GaussPointCounts rule = chooseGaussRulesNoVisibility(input(2, magnitudes, 0.01));
  EXPECT_EQ(rule, (GaussPointCounts{3, 3, 1, 1}));
  EXPECT_EQ(ruleEvaluations(rule), 9u);
  const int full = 3;
  EXPECT_EQ(ruleEvaluations({full, full, full, full}), 81u);
}

TEST(AdaptiveGauss, EachSourceAxisFollowsItsHighestSignificantOrder) {
  // Order i along u is significant when any B_(i,j) is; order j along v likewise.
  EXPECT_EQ(chooseGaussRulesNoVisibility(input(3, coefficients(3, {{0, 0}, {2, 0}}), 0.5)),
            (GaussPointCounts{4, 4, 3, 1}));
  EXPECT_EQ(chooseGaussRulesNoVisibility(input(3, coefficients(3, {{0, 1}}), 0.5)),
            (GaussPointCounts{4, 4, 1, 2}));
  EXPECT_EQ(chooseGaussRulesNoVisibility(input(3, coefficients(3, {{1, 2}}), 0.5)),
            (GaussPointCounts{4, 4, 2, 3}));
  EXPECT_EQ(chooseGaussRulesNoVisibility(input(3, coefficients(3, {{3, 3}}), 0.5)),
            (GaussPointCounts{4, 4, 4, 4}));
  // The highest significant order counts, even with insignificant orders below it.
  EXPECT_EQ(chooseGaussRulesNoVisibility(input(3, coefficients(3, {{3, 0}}), 0.5)),
            (GaussPointCounts{4, 4, 4, 1}));
  // The receiver always gets d+1 points per axis; degree 0 is one point everywhere.
  EXPECT_EQ(chooseGaussRulesNoVisibility(input(1, coefficients(1, {}), 0.5)),
            (GaussPointCounts{2, 2, 1, 1}));
  EXPECT_EQ(chooseGaussRulesNoVisibility(input(0, coefficients(0, {{0, 0}}), 0.5)),
            (GaussPointCounts{1, 1, 1, 1}));
}

TEST(AdaptiveGauss, ThresholdIsStrictAndMagnitudesAreAbsolute) {
  EXPECT_EQ(chooseGaussRulesNoVisibility(input(2, coefficients(2, {{2, 2}}, 0.5), 0.5)),
            (GaussPointCounts{3, 3, 1, 1}));
  EXPECT_EQ(chooseGaussRulesNoVisibility(input(2, coefficients(2, {{2, 2}}, 0.51), 0.5)),
            (GaussPointCounts{3, 3, 3, 3}));
  EXPECT_EQ(chooseGaussRulesNoVisibility(input(2, coefficients(2, {{2, 1}}, -0.7), 0.5)),
            (GaussPointCounts{3, 3, 3, 2}));
}

TEST(AdaptiveGauss, AxisMagnitudesAreMaximaOverTheOtherAxis) {
  const std::vector<double> magnitudes = {1, -5, 2, 3};  // d = 1: (0,0) (0,1) (1,0) (1,1)
  double alongU[2], alongV[2];
  axisMagnitudes(1, magnitudes.data(), alongU, alongV);
  EXPECT_EQ(alongU[0], 5.0);
  EXPECT_EQ(alongU[1], 3.0);
  EXPECT_EQ(alongV[0], 2.0);
  EXPECT_EQ(alongV[1], 5.0);
  EXPECT_EQ(pointsForAxis(alongU, 2, 4.0), 1);
  EXPECT_EQ(pointsForAxis(alongU, 2, 2.9), 2);
}

TEST(AdaptiveGauss, PartialVisibilityAddsOnePointToOneShortSourceAxis) {
  const auto constant = coefficients(3, {{0, 0}});
  int grewU = 0, grewV = 0;
  for (std::uint64_t seed = 0; seed < 200; ++seed) {
    PhiloxStream generator(seed, 0);
    const GaussPointCounts rule = chooseGaussRules(input(3, constant, 0.5, true), generator);
    ASSERT_EQ(rule[0], 4);
    ASSERT_EQ(rule[1], 4);
    ASSERT_EQ(rule[2] + rule[3], 3) << "exactly one axis grows by one point";
    (rule[2] == 2 ? grewU : grewV) += 1;
    // The same seed gives the same choice.
    PhiloxStream again(seed, 0);
    EXPECT_EQ(chooseGaussRules(input(3, constant, 0.5, true), again), rule);
  }
  // Both axes are chosen, about equally often (binomial(200, 1/2): 6 sigma is 42).
  EXPECT_GT(grewU, 100 - 42);
  EXPECT_GT(grewV, 100 - 42);

  PhiloxStream generator(7, 0);
  // Only the short axis can grow; a full rule stays full; unoccluded links never grow.
  EXPECT_EQ(chooseGaussRules(input(3, coefficients(3, {{3, 0}}), 0.5, true), generator),
            (GaussPointCounts{4, 4, 4, 2}));
  EXPECT_EQ(chooseGaussRules(input(3, coefficients(3, {{1, 3}}), 0.5, true), generator),
            (GaussPointCounts{4, 4, 3, 4}));
  EXPECT_EQ(chooseGaussRules(input(3, coefficients(3, {{3, 3}}), 0.5, true), generator),
            (GaussPointCounts{4, 4, 4, 4}));
  EXPECT_EQ(chooseGaussRules(input(3, constant, 0.5, false), generator),
            (GaussPointCounts{4, 4, 1, 1}));
}

TEST(AdaptiveGauss, LinkSeedsDependOnTheOrderedPairOfElements) {
  EXPECT_EQ(linkSeed(0, 3, 5), linkSeed(0, 3, 5));
  EXPECT_NE(linkSeed(0, 3, 5), linkSeed(0, 5, 3));
  EXPECT_NE(linkSeed(0, 3, 5), linkSeed(1, 3, 5));
  EXPECT_NE(linkSeed(0, 0, 1), linkSeed(0, 1, 0));
}

}  // namespace
}  // namespace radquad
