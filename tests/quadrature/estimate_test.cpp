// The estimate of a mean from independent draws against the two-pass formulas, on draws
// whose deviation is tiny against their mean (where a one-pass sum of squares fails), and the
// standard error of the mean against its distribution over many independent estimates.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "quadrature/estimate.h"

namespace radquad {
namespace {

TEST(EntrywiseMoments, AgreeWithTheTwoPassFormulas) {
  std::mt19937_64 random(9);
  std::normal_distribution<double> normal(1e6, 1.0);  // a large mean: cancellation-prone
  std::vector<Eigen::MatrixXd> draws;
  EntrywiseMoments moments;
  for (int k = 0; k < 50; ++k) {
    Eigen::MatrixXd draw(2, 3);
    for (int e = 0; e < 6; ++e) draw.data()[e] = normal(random);
    draws.push_back(draw);
    moments.add(draw);
  }
  Eigen::MatrixXd mean = Eigen::MatrixXd::Zero(2, 3), squares = Eigen::MatrixXd::Zero(2, 3);
  for (const auto& draw : draws) mean += draw / 50.0;
  for (const auto& draw : draws) squares += (draw - mean).cwiseAbs2();
  const Eigen::MatrixXd deviation = (squares / 49.0).cwiseSqrt();
  EXPECT_EQ(moments.count(), 50u);
  EXPECT_LE((moments.mean() - mean).cwiseAbs().maxCoeff(), 1e-9);
  EXPECT_LE((moments.sampleDeviation() - deviation).cwiseAbs().maxCoeff(), 1e-9);
  EXPECT_LE((moments.standardError() - deviation / std::sqrt(50.0)).cwiseAbs().maxCoeff(), 1e-9);
  // The naive one-pass formula sum x^2 / n - mean^2 is off by far more than that here:
  // x^2 ~ 1e12 carries an absolute rounding of about 1e-4, against a variance of 1.
}

TEST(EntrywiseMoments, OneDrawHasNoSpreadAndScalarsAreOneByOne) {
  EntrywiseMoments one;
  one.add(Eigen::MatrixXd::Constant(2, 3, 4.0));
  EXPECT_EQ(one.sampleDeviation(), Eigen::MatrixXd::Zero(2, 3));
  EXPECT_EQ(one.standardError(), Eigen::MatrixXd::Zero(2, 3));
  EntrywiseMoments scalar;
  for (const double x : {1.0, 2.0, 3.0, 4.0}) scalar.add(x);
  EXPECT_DOUBLE_EQ(scalar.mean()(0, 0), 2.5);
  // Sample variance of 1..4: sum (x - 2.5)^2 / 3 = 5/3.
  EXPECT_DOUBLE_EQ(scalar.sampleDeviation()(0, 0), std::sqrt(5.0 / 3.0));
  EXPECT_DOUBLE_EQ(scalar.standardError()(0, 0), std::sqrt(5.0 / 3.0) / 2.0);
}

TEST(EntrywiseMoments, StandardErrorMatchesTheSpreadOfIndependentMeans) {
  // 4000 estimates, each the mean of 20 uniform draws on [0,1] (variance 1/12): the
  // estimated standard errors must average to sqrt(1/12/20) (up to the bias of the sample
  // deviation, under 2% for n = 20), and the means must spread by the same amount.
  std::mt19937_64 random(17);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  const double truth = std::sqrt(1.0 / 12.0 / 20.0);
  double meanOfErrors = 0.0, spread = 0.0;
  for (int e = 0; e < 4000; ++e) {
    EntrywiseMoments moments;
    for (int k = 0; k < 20; ++k) moments.add(uniform(random));
    meanOfErrors += moments.standardError()(0, 0) / 4000.0;
    spread += (moments.mean()(0, 0) - 0.5) * (moments.mean()(0, 0) - 0.5) / 4000.0;
  }
  EXPECT_NEAR(meanOfErrors / truth, 1.0, 0.03);
  EXPECT_NEAR(std::sqrt(spread) / truth, 1.0, 0.04);
}

}  // namespace
}  // namespace radquad
