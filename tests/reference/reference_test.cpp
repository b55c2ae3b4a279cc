// The paper's reference, its standard error, and the gold references.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "kernel/occluder_scene.h"
#include "reference/gold_reference.h"
#include "reference/point_polygon_form_factor.h"
#include "reference/stratified_reference.h"
#include "tests/support/analytic_form_factors.h"

namespace radquad {
namespace {

Patch unitReceiver() {
  return Patch::make({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, "receiver");
}
Patch facingSource() {
  return Patch::make({0, 1, 1}, {1, 0, 0}, {0, -1, 0}, "source");
}

// A blocker half way between the parallel squares, covering about half of the rays.
struct OccludedLink {
  OccluderScene scene;
  Link link;
  OccludedLink() {
    scene.addParallelogram(Patch::make({-0.2, -0.2, 0.5}, {0.7, 0, 0}, {0, 1.4, 0}, "blocker"));
    scene.commit();
    link = Link{unitReceiver(), facingSource(), &scene};
  }
};

// Over many seeds, the spread of the reference values equals the standard error it reports:
// the ratio of the observed standard deviation over 200 seeds to the root-mean-square of the
// reported errors lies within 15% of 1 (the observed deviation is itself uncertain by
// 1/sqrt(2 * 199) = 5%, the mean reported variance by about 3%), for every coefficient.
void expectCalibrated(const Link& link, int degree) {
  constexpr int kSeeds = 1000;
  const int functions = (degree + 1) * (degree + 1);
  Eigen::MatrixXd sum = Eigen::MatrixXd::Zero(functions, functions), squares = sum,
                  reportedVariance = sum;
  for (int seed = 0; seed < kSeeds; ++seed) {
    const ReferenceEstimate estimate =
        stratifiedReference(link, degree, std::uint64_t(seed) * 7919);
    ASSERT_EQ(estimate.integral.kernelEvaluations, 10000u);
    sum += estimate.integral.coupling;
    squares += estimate.integral.coupling.cwiseAbs2();
    reportedVariance += estimate.couplingStandardError.cwiseAbs2();
  }
  const Eigen::MatrixXd mean = sum / kSeeds;
  const Eigen::MatrixXd observed =
      ((squares / kSeeds - mean.cwiseAbs2()) * (kSeeds / (kSeeds - 1.0))).cwiseSqrt();
  const Eigen::MatrixXd reported = (reportedVariance / kSeeds).cwiseSqrt();
  for (int a = 0; a < functions; ++a) {
    for (int b = 0; b < functions; ++b) {
      const double ratio = observed(a, b) / reported(a, b);
      EXPECT_GT(ratio, 0.85) << "K[" << a << "][" << b << "] degree " << degree;
      EXPECT_LT(ratio, 1.15) << "K[" << a << "][" << b << "] degree " << degree;
    }
  }
}

TEST(StratifiedReference, StandardErrorIsCalibratedOnAnUnoccludedLink) {
  expectCalibrated(Link{unitReceiver(), facingSource(), nullptr}, 1);
}

TEST(StratifiedReference, StandardErrorIsCalibratedOnAPartiallyOccludedLink) {
  OccludedLink occluded;
  expectCalibrated(occluded.link, 0);
}

// With the gold known far more precisely, z = (reference - gold) / reported error. The
// reported draw is replicate 0 of the R = 10 whose sample standard deviation is the reported
// error, so z is not Student's t (its numerator is part of its denominator): for normal errors
// P(|z| < 2) = 0.9586 (2e6 draws of 10 standard normals, z = x_0 / s). Over 1000 seeds the
// observed fraction lies in [0.936, 0.981] (3.5 binomial standard deviations of 0.0063).
TEST(StratifiedReference, ErrorsAgainstTheGoldFollowTheReportedStandardError) {
  const Link link{unitReceiver(), facingSource(), nullptr};
  const GoldReference gold = goldReference(link, 0, 0);
  ASSERT_EQ(gold.method, "gauss product");
  int within = 0;
  constexpr int kSeeds = 200;
  for (int seed = 0; seed < kSeeds; ++seed) {
    const ReferenceEstimate estimate = stratifiedReference(link, 0, 1000 + std::uint64_t(seed));
    const double z =
        (estimate.integral.formFactor - gold.formFactor) / estimate.formFactorStandardError;
    within += std::fabs(z) < 2.0;
  }
  EXPECT_GE(within, int(0.936 * kSeeds));
  EXPECT_LE(within, int(0.981 * kSeeds));
}

TEST(GoldReference, GaussGoldMatchesTheClosedFormOfParallelSquares) {
  const Link link{unitReceiver(), facingSource(), nullptr};
  const GoldReference gold = goldReference(link, 2, 0);
  EXPECT_EQ(gold.method, "gauss product");
  EXPECT_TRUE(gold.converged);
  EXPECT_NEAR(gold.formFactor, analytic::parallelRectangles(1, 1, 1), 1e-10);
  ASSERT_TRUE(gold.lambert.has_value());
  EXPECT_TRUE(gold.lambert->converged);
  EXPECT_LT(gold.lambert->maxDifference, 1e-9);
}

TEST(GoldReference, LambertColumnMatchesTheClosedFormOfPerpendicularSquares) {
  // Receiver on the floor, source a wall sharing the edge y = 0, facing +y.
  const Patch receiver = Patch::make({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, "receiver");
  const Patch source = Patch::make({0, 0, 0}, {0, 0, 1}, {1, 0, 0}, "source");
  ASSERT_NEAR(source.normal.y(), 1.0, 1e-15);
  const Link link{receiver, source, nullptr};
  const LambertCheck check = lambertColumn(link, 0, 1e-9);
  // The inner integral is exact; the outer Gauss rule meets the logarithmic edge singularity.
  EXPECT_NEAR(check.column[0], analytic::perpendicularRectangles(1, 1, 1), 1e-5);
}

TEST(GoldReference, LambertAgreesWithGaussWhenTheSourceCrossesTheReceiversPlane) {
  // The source is tilted through the receiver's plane: clipping handles cos(theta) < 0.
  const Patch receiver = Patch::make({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, "receiver");
  const Patch source = Patch::make({2.0, 0, -0.5}, {-0.3, 0, 1.5}, {0, 1, 0}, "source");
  ASSERT_LT(source.normal.x(), 0.0);  // faces the receiver
  const Link link{receiver, source, nullptr};
  // The clamped cosine leaves a kink that the Gauss sequence resolves only algebraically: it
  // does not converge, and the gold falls to exact visibility, which clips at the kink.
  const GoldReference gold = goldReference(link, 1, 0);
  EXPECT_EQ(gold.method, "exact visibility");
  EXPECT_TRUE(gold.converged);
  ASSERT_GT(gold.formFactor, 0.01);
  const double largest = gold.coupling.cwiseAbs().maxCoeff();
  EXPECT_LT(gold.couplingError.maxCoeff(), 1e-7 * largest);
  const LambertCheck check = lambertColumn(link, 1, 1e-9);
  EXPECT_LT((check.column - gold.coupling.col(0)).cwiseAbs().maxCoeff(), 2e-4 * largest);
}

TEST(PointToPatchFormFactor, MatchesTheClosedFormAtTheCentreAndIsZeroFromBehind) {
  const Patch source = Patch::make({-1, -1.5, 2}, {0, 3, 0}, {2, 0, 0}, "source");  // faces -z
  ASSERT_NEAR(source.normal.z(), -1.0, 1e-15);
  const double expected = 4.0 * analytic::pointToCornerRectangle(1.0, 1.5, 2.0);
  EXPECT_NEAR(pointToPatchFormFactor({0, 0, 0}, {0, 0, 1}, source), expected, 1e-14);
  EXPECT_EQ(pointToPatchFormFactor({0, 0, 3}, {0, 0, -1}, source), 0.0);
  // A point looking away sees nothing.
  EXPECT_EQ(pointToPatchFormFactor({0, 0, 0}, {0, 0, -1}, source), 0.0);
}

TEST(GoldReference, DenseStratifiedGoldOnAnOccludedLinkIsFarTighterAndAgrees) {
  OccludedLink occluded;
  GoldOptions options;
  options.method = GoldMethod::stratified;
  const GoldReference gold = goldReference(occluded.link, 0, 5, options);
  EXPECT_EQ(gold.method, "dense stratified");
  const ReferenceEstimate reference = stratifiedReference(occluded.link, 0, 5);
  EXPECT_LT(gold.formFactorError, reference.formFactorStandardError / 5.0);
  EXPECT_LT(std::fabs(reference.integral.formFactor - gold.formFactor),
            4.0 * std::hypot(reference.formFactorStandardError, gold.formFactorError));
  // The visible part: less than the unoccluded form factor, more than none.
  EXPECT_GT(gold.formFactor, 0.05);
  EXPECT_LT(gold.formFactor, analytic::parallelRectangles(1, 1, 1) - 0.05);
}

}  // namespace
}  // namespace radquad
