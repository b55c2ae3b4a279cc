// The study's metrics against hand computations.
#include <gtest/gtest.h>

#include <cmath>

#include "experiments/study/study_metrics.h"

namespace radquad {
namespace {

// c_k = int_0^1 |phi_k|: c_0 = 1, c_1 = sqrt(3)/2, and for phi_2 = sqrt(5)(6t^2 - 6t + 1),
// whose roots are t = 1/2 -+ 1/(2 sqrt 3), integrating |3x^2 - 1|/2 over x in [-1,1] gives
// c_2 = sqrt(5) * 2/(3 sqrt 3).
const double kC[3] = {1.0, std::sqrt(3.0) / 2.0, std::sqrt(5.0) * 2.0 / (3.0 * std::sqrt(3.0))};

TEST(StudyMetrics, RelativeErrorOfTheConstantCoefficient) {
  Eigen::MatrixXd reference(1, 1), estimate(1, 1);
  reference << 0.25;
  estimate << 0.2;
  EXPECT_DOUBLE_EQ(relativeError(estimate, reference), 0.2);
}

TEST(StudyMetrics, L1BoundWeighsEachReceiverFunctionByItsAbsoluteIntegral) {
  // Quadratic bases: 9 functions, a = i*3 + j. Differences only in column b = 4.
  Eigen::MatrixXd difference = Eigen::MatrixXd::Zero(9, 9);
  difference(0, 4) = 0.5;    // (0,0): c0 c0
  difference(5, 4) = -0.25;  // (1,2): c1 c2
  difference(8, 4) = 0.125;  // (2,2): c2 c2
  const double area = 4.0;   // 1/sqrt(A_r) = 1/2
  const std::vector<double> bound = l1ErrorBound(difference, area);
  ASSERT_EQ(bound.size(), 9u);
  const double expected =
      0.5 * (0.5 * kC[0] * kC[0] + 0.25 * kC[1] * kC[2] + 0.125 * kC[2] * kC[2]);
  EXPECT_NEAR(bound[4], expected, 1e-14);
  for (int b = 0; b < 9; ++b) {
    if (b != 4) {
      EXPECT_EQ(bound[std::size_t(b)], 0.0) << "source function " << b;
    }
  }
}

TEST(StudyMetrics, L1BoundOfAConstantBasisIsTheAbsoluteErrorPerRootArea) {
  // With d = 0, U_0 = |dK00| / sqrt(A_r) = |dF| sqrt(A_r/A_s)/sqrt(A_r) (docs/design.md).
  Eigen::MatrixXd difference(1, 1);
  difference << -0.3;
  EXPECT_NEAR(l1ErrorBound(difference, 9.0)[0], 0.1, 1e-15);
}

TEST(StudyMetrics, SummaryStatistics) {
  const SummaryStatistics s = summarize({4.0, 1.0, 3.0, 2.0, 10.0});
  EXPECT_DOUBLE_EQ(s.mean, 4.0);
  EXPECT_DOUBLE_EQ(s.median, 3.0);
  // Sorted 1,2,3,4,10: position 0.9*4 = 3.6 -> 4 + 0.6*(10-4).
  EXPECT_DOUBLE_EQ(s.p90, 7.6);
  EXPECT_DOUBLE_EQ(s.max, 10.0);
  // Deviations -3,-2,-1,0,6: squares 50, sample variance 12.5, sem sqrt(12.5/5).
  EXPECT_DOUBLE_EQ(s.sem, std::sqrt(2.5));
  // The largest link carries 10 of the sum 20.
  EXPECT_DOUBLE_EQ(s.largestShare, 0.5);
  EXPECT_EQ(summarize({0.0, 0.0}).largestShare, 0.0);
  EXPECT_EQ(summarize({}).count, 0u);
  EXPECT_EQ(summarize({7.0}).sem, 0.0);
}

TEST(StudyMetrics, RelativeFrobeniusErrorIsTheNormOfTheDifferenceOverTheNorm) {
  Eigen::MatrixXd reference(2, 2), estimate(2, 2);
  reference << 3, 0, 0, 4;  // norm 5
  estimate << 3, 1, 0, 4;   // difference norm 1
  EXPECT_DOUBLE_EQ(relativeFrobeniusError(estimate, reference), 0.2);
  // Scale-free: the same relative error for a coupling a thousand times larger.
  EXPECT_DOUBLE_EQ(relativeFrobeniusError(1000 * estimate, 1000 * reference), 0.2);
}

}  // namespace
}  // namespace radquad
