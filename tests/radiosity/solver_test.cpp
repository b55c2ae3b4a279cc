// The solver against closed forms: the white furnace and two opposed squares; and the
// independence of the result from the thread count.
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include "radiosity/solver.h"
#include "tests/radiosity/scenes_for_tests.h"

namespace radquad {
namespace {

using testing::furnaceScene;
using testing::opposedSquaresScene;

struct FurnaceCase {
  int degree;
  double minArea;
  double tolerance;  // relative
};

class FurnaceTest : public ::testing::TestWithParam<FurnaceCase> {};

// Every surface of a closed box emitting E with reflectance rho: B = E / (1 - rho) exactly.
// The error comes from the couplings' quadrature (their rows must sum to the full form
// factor 1); it shrinks with the smallest element (min area).
TEST_P(FurnaceTest, RadiosityIsEmissionOverOneMinusReflectance) {
  const FurnaceCase& param = GetParam();
  const double emission = 1.0, rho = 0.5;
  const Scene scene = furnaceScene(emission, rho);
  SolverOptions options;
  options.degree = param.degree;
  options.minArea = param.minArea;
  options.bfEpsilon = 0.01;
  Solver solver(scene, options);
  solver.solve();
  ASSERT_TRUE(solver.statistics().converged);
  const double exact = emission / (1.0 - rho);
  for (std::size_t p = 0; p < scene.patches.size(); ++p) {
    const Eigen::Vector3d mean = solver.hierarchy()[int(p)].meanRadiosity();
    for (int c = 0; c < 3; ++c) {
      EXPECT_NEAR(mean[c], exact, param.tolerance * exact)
          << "degree " << param.degree << " face " << p << " channel " << c;
    }
  }
  // Pointwise too, at a few points away from the edges.
  for (double u : {0.3, 0.5, 0.7}) {
    EXPECT_NEAR(solver.hierarchy().radiosityAt(0, u, 0.5)[0], exact, 2 * param.tolerance * exact)
        << "degree " << param.degree << " at u = " << u;
  }
}

INSTANTIATE_TEST_SUITE_P(Degrees, FurnaceTest,
                         ::testing::Values(FurnaceCase{0, 1e-3, 0.015},
                                           FurnaceCase{2, 4e-3, 0.01}));

// A black emitter (E = 1) facing a receiver with reflectance rho: the receiver's mean
// radiosity is rho F, F the closed-form form factor between the squares.
TEST(OpposedSquaresTest, ReceiverMeanRadiosityIsReflectanceTimesFormFactor) {
  const double rho = 0.6;
  const Scene scene = opposedSquaresScene(rho);
  for (int degree = 0; degree <= 3; ++degree) {
    SolverOptions options;
    options.degree = degree;
    options.bfEpsilon = 0.01;
    Solver solver(scene, options);
    solver.solve();
    const double expected = rho * testing::kOpposedUnitSquaresFormFactor;
    const Eigen::Vector3d mean = solver.hierarchy()[1].meanRadiosity();
    EXPECT_NEAR(mean[0], expected, 0.005 * expected) << "degree " << degree;
    // The emitter is black: it shows its emission only.
    EXPECT_NEAR(solver.hierarchy()[0].meanRadiosity()[0], 1.0, 1e-12) << "degree " << degree;
  }
}

TEST(SolverDeterminismTest, ResultDoesNotDependOnTheThreadCount) {
  const Scene scene = *builtinScene("cornell");
  SolverOptions options;
  options.degree = 1;
  options.bfEpsilon = 0.5;
  auto solveWith = [&](std::size_t threads) {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
    auto solver = std::make_unique<Solver>(scene, options);
    solver->solve();
    return solver;
  };
  const auto one = solveWith(1);
  const auto two = solveWith(2);
  ASSERT_EQ(one->hierarchy().size(), two->hierarchy().size());
  EXPECT_EQ(one->statistics().kernelEvaluations, two->statistics().kernelEvaluations);
  for (std::size_t e = 0; e < one->hierarchy().size(); ++e) {
    ASSERT_EQ(one->hierarchy()[int(e)].radiosity, two->hierarchy()[int(e)].radiosity)
        << "element " << e;
  }
}

// The elements' lists of active links are brought up to date after each refinement pass
// rather than rebuilt (Solver::updateElementLinks): after a solve whose refinement passes came
// after iterations (the active links changed between progress reports), every element lists
// exactly the active links it receives, in link order, as a rebuild from the links makes them.
TEST(SolverElementLinksTest, EveryElementListsItsActiveLinksInOrderAfterLaterRefinements) {
  const Scene scene = *builtinScene("cornell");
  SolverOptions options;
  options.degree = 1;
  options.bfEpsilon = 0.2;
  std::vector<std::size_t> active;
  options.progress = [&](const SolveProgress& progress) { active.push_back(progress.activeLinks); };
  Solver solver(scene, options);
  solver.solve();
  ASSERT_TRUE(solver.statistics().converged);
  int changes = 0;
  for (std::size_t k = 1; k < active.size(); ++k) changes += active[k] != active[k - 1] ? 1 : 0;
  ASSERT_GE(changes, 2) << "the solve must refine after iterating, more than once";
  std::vector<std::vector<int>> expected(solver.hierarchy().size());
  std::size_t split = 0;
  for (std::size_t k = 0; k < solver.links().size(); ++k) {
    const SolverLink& link = solver.links()[k];
    if (link.active) expected[std::size_t(link.receiver)].push_back(int(k));
    split += link.split ? 1 : 0;
  }
  ASSERT_GT(split, 0u);
  for (std::size_t e = 0; e < expected.size(); ++e) {
    ASSERT_EQ(solver.hierarchy()[int(e)].links, expected[e]) << "element " << e;
  }
}

}  // namespace
}  // namespace radquad

namespace radquad {
namespace {

// The per-patch comparison of two solutions: the opposed squares with receiver reflectance
// 0.6 against 0.3 (mean radiosity rho F for a black emitter of E = 1): the receiver differs
// by exactly 0.6 / 0.3 - 1 = 1 in every channel, the emitter (B = E) not at all.
TEST(PatchDifferenceTest, TheReceiverOfTwiceTheReflectanceIsTwiceAsBright) {
  const Scene bright = testing::opposedSquaresScene(0.6);
  const Scene dim = testing::opposedSquaresScene(0.3);
  SolverOptions options;
  options.degree = 1;
  Solver a(bright, options), b(dim, options);
  a.solve();
  b.solve();
  const Hierarchy::PatchDifference same = a.hierarchy().largestPatchDifference(a.hierarchy());
  EXPECT_EQ(same.value, 0.0);
  const Hierarchy::PatchDifference difference = a.hierarchy().largestPatchDifference(b.hierarchy());
  EXPECT_EQ(difference.patch, 1);
  EXPECT_EQ(difference.channel, 0);
  EXPECT_NEAR(difference.value, 1.0, 1e-9);
  const Hierarchy::PatchDifference reversed = b.hierarchy().largestPatchDifference(a.hierarchy());
  EXPECT_NEAR(reversed.value, -0.5, 1e-9);
}

}  // namespace
}  // namespace radquad
