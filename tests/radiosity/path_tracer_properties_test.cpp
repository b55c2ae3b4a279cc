// Properties of the Monte Carlo path tracer: calibrated standard errors, results that do not
// depend on the thread count, one-sided patches that occlude from both sides, and errors.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>

#include "kernel/input_error.h"
#include "radiosity/path_tracer.h"
#include "tests/radiosity/scenes_for_tests.h"
#include "tests/support/analytic_form_factors.h"

namespace radquad {
namespace {

using Vec = Eigen::Vector3d;

TraceResult trace(const Scene& scene, std::uint64_t samples, std::uint64_t seed = 0,
                  int threads = 0) {
  TraceOptions options;
  options.samples = samples;
  options.seed = seed;
  options.threads = threads;
  return tracePatches(scene, options);
}

// Over 100 seeds, |estimate - exact| falls within one standard error about 68% of the time
// and within two about 95% (the opposed squares, whose estimate is close to normal at 1024
// samples). A biased estimate or a wrong standard error moves these fractions.
TEST(PathTracerCalibrationTest, ErrorsFallWithinTheirStandardErrorsAtTheNominalRate) {
  const double rho = 0.5;
  const double exact = rho * analytic::parallelRectangles(1.0, 1.0, 1.0);
  const Scene scene = testing::opposedSquaresScene(rho);
  const int runs = 100;
  int withinOne = 0, withinTwo = 0;
  double sumOfScores = 0.0;
  for (int seed = 0; seed < runs; ++seed) {
    const PatchTrace receiver = trace(scene, 1024, std::uint64_t(seed)).patches[1];
    const double score = (receiver.meanRadiosity[0] - exact) / receiver.standardError[0];
    withinOne += std::abs(score) <= 1.0;
    withinTwo += std::abs(score) <= 2.0;
    sumOfScores += score;
  }
  EXPECT_GE(withinOne, 0.55 * runs);
  EXPECT_LE(withinOne, 0.85 * runs);
  EXPECT_GE(withinTwo, 0.85 * runs);
  // The mean score of unbiased runs has standard deviation 1/sqrt(runs) = 0.1.
  EXPECT_LT(std::abs(sumOfScores / runs), 0.3);
}

void expectSameResults(const TraceResult& a, const TraceResult& b) {
  ASSERT_EQ(a.patches.size(), b.patches.size());
  for (std::size_t p = 0; p < a.patches.size(); ++p) {
    for (int c = 0; c < 3; ++c) {  // bit for bit
      EXPECT_EQ(a.patches[p].meanRadiosity[c], b.patches[p].meanRadiosity[c]) << p;
      EXPECT_EQ(a.patches[p].standardError[c], b.patches[p].standardError[c]) << p;
    }
  }
  EXPECT_EQ(a.paths, b.paths);
  EXPECT_EQ(a.hitRays, b.hitRays);
  EXPECT_EQ(a.shadowRays, b.shadowRays);
}

// 2500 samples make three chunks per patch, the last one partial.
TEST(PathTracerDeterminismTest, ResultsDoNotDependOnTheThreadCountOrTheRun) {
  const Scene scene = *builtinScene("cornell");
  const TraceResult one = trace(scene, 2500, 7, 1);
  const TraceResult two = trace(scene, 2500, 7, 2);
  const TraceResult again = trace(scene, 2500, 7, 2);
  expectSameResults(one, two);
  expectSameResults(two, again);
  EXPECT_EQ(one.paths, 2500u * scene.patches.size());
}

TEST(PathTracerDeterminismTest, DifferentSeedsGiveDifferentValues) {
  const Scene scene = *builtinScene("cornell");
  const TraceResult first = trace(scene, 256, 0);
  const TraceResult second = trace(scene, 256, 1);
  for (std::size_t p = 0; p < scene.patches.size(); ++p) {
    EXPECT_NE(first.patches[p].meanRadiosity[0], second.patches[p].meanRadiosity[0]) << p;
  }
}

// The emitter turned away from the receiver: not one path reaches the receiver's side.
TEST(PathTracerOneSidednessTest, AnEmitterFacingAwayGivesExactlyZero) {
  Scene scene = testing::opposedSquaresScene(0.5);
  scene.patches[0].patch = Patch::make(Vec::Zero(), Vec::UnitY(), Vec::UnitX(), "emitter");
  ASSERT_LT(scene.patches[0].patch.normal.z(), -0.99);
  const TraceResult result = trace(scene, 4096);
  EXPECT_EQ(result.patches[1].meanRadiosity, Vec::Zero());
  EXPECT_EQ(result.patches[1].standardError, Vec::Zero());
  EXPECT_GT(result.shadowRays + result.hitRays, 0u);
}

// A 3 x 3 blocker halfway between the squares hides the emitter from every receiver point,
// whichever way it faces: facing the emitter, it reflects light back down and shows the
// receiver its dark back side (which stops the shadow rays); facing the receiver, it gets
// no light (the emitter is behind it).
TEST(PathTracerOneSidednessTest, ABlockerBetweenTheSquaresGivesExactlyZero) {
  for (bool facingEmitter : {true, false}) {
    Scene scene = testing::opposedSquaresScene(0.5);
    const Vec corner(-1.0, -1.0, 0.5), a = 3.0 * Vec::UnitX(), b = 3.0 * Vec::UnitY();
    scene.patches.push_back(ScenePatch{
        "blocker",
        facingEmitter ? Patch::make(corner, b, a, "blocker") : Patch::make(corner, a, b, "blocker"),
        Vec::Constant(0.5), Vec::Zero()});
    ASSERT_EQ(scene.patches[2].patch.normal.z() < 0.0, facingEmitter);
    const TraceResult result = trace(scene, 4096);
    EXPECT_EQ(result.patches[1].meanRadiosity, Vec::Zero()) << facingEmitter;
    EXPECT_EQ(result.patches[1].standardError, Vec::Zero()) << facingEmitter;
    if (facingEmitter) {
      EXPECT_GT(result.patches[2].meanRadiosity[0], 0.01);
    } else {
      EXPECT_EQ(result.patches[2].meanRadiosity, Vec::Zero());
    }
  }
}

TEST(PathTracerInputTest, SampleCountsOutsideTheRangeAreRejected) {
  const Scene scene = testing::opposedSquaresScene(0.5);
  EXPECT_THROW(trace(scene, 0), std::invalid_argument);
  EXPECT_THROW(trace(scene, kMaxTraceSamples + 1), std::invalid_argument);
  EXPECT_THROW(trace(scene, 16, 0, -1), std::invalid_argument);
}

// One sample per patch: a mean but no standard error.
TEST(PathTracerInputTest, OneSampleHasNoStandardError) {
  const TraceResult result = trace(testing::opposedSquaresScene(0.5), 1);
  EXPECT_TRUE(std::isfinite(result.patches[1].meanRadiosity[0]));
  EXPECT_TRUE(std::isnan(result.patches[1].standardError[0]));
}

// An emission near the largest double makes the sample variance overflow.
TEST(PathTracerInputTest, ANonFiniteEstimateIsAComputationError) {
  Scene scene = testing::opposedSquaresScene(0.5);
  scene.patches[0].emission = Vec::Constant(std::numeric_limits<double>::max());
  try {
    trace(scene, 64);
    FAIL() << "no ComputationError";
  } catch (const ComputationError& error) {
    EXPECT_NE(std::string(error.what()).find("patches[1] (receiver)"), std::string::npos)
        << error.what();
  }
}

}  // namespace
}  // namespace radquad
