// The exact gold (reference/exact_gold.h) against closed forms: parallel and perpendicular
// squares, occluders lying or standing on the receiver (the critical and jump lines), skew
// polygons, higher degrees against the converged Gauss gold, and a symmetric half blocker;
// and which links the gold reference sends to it.
#include <gtest/gtest.h>

#include <Eigen/Core>

#include <cmath>
#include <string>
#include <vector>

#include "kernel/occluder_scene.h"
#include "kernel/patch_intersection.h"
#include "reference/exact_gold.h"
#include "reference/gold_reference.h"
#include "tests/support/analytic_form_factors.h"
#include "tests/support/polygon_form_factor.h"

namespace radquad {
namespace {

std::vector<Eigen::Vector3d> cornersOf(const Patch& patch) {
  const auto corners = patch.corners();
  return {corners.begin(), corners.end()};
}

TEST(ExactGold, ParallelAndPerpendicularSquaresMatchTheirClosedForms) {
  const Patch receiver = Patch::make({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, "receiver");
  const Patch facing = Patch::make({0, 1, 1}, {1, 0, 0}, {0, -1, 0}, "source");
  const ExactGold parallel = exactGold(Link{receiver, facing, nullptr}, 0);
  EXPECT_TRUE(parallel.converged);
  EXPECT_NEAR(parallel.formFactor, analytic::parallelRectangles(1, 1, 1), 1e-9);
  EXPECT_LE(parallel.formFactorError, 1e-7 * parallel.formFactor);
  // Sharing an edge at right angles: the kernel is singular along the common edge.
  const Patch wall = Patch::make({0, 0, 0}, {0, 0, 1}, {1, 0, 0}, "wall");  // faces +y
  ASSERT_NEAR(wall.normal.y(), 1.0, 1e-15);
  const ExactGold touching = exactGold(Link{receiver, wall, nullptr}, 0);
  EXPECT_TRUE(touching.converged);
  const double expected = analytic::perpendicularRectangles(1, 1, 1);
  EXPECT_NEAR(touching.formFactor, expected, 2e-7 * expected);
}

TEST(ExactGold, ARugLyingOnTheReceiverHidesNothing) {
  // A rectangle lying in the receiver's plane (either way up, partly past its edge) is seen
  // edge-on from every receiver point: it hides nothing, and the gold is the unoccluded one
  // (degree 0: the closed form; degree 2: the exact gold without occluders), whichever outer
  // integration it takes.
  const Patch receiver = Patch::make({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, "receiver");
  const Patch source = Patch::make({0, 1, 1}, {1, 0, 0}, {0, -1, 0}, "source");
  const ExactGold open2 = exactGold(Link{receiver, source, nullptr}, 2);
  ASSERT_TRUE(open2.converged);
  for (bool up : {true, false}) {
    OccluderScene scene;
    scene.addParallelogram(up ? Patch::make({0.2, 0.3, 0}, {0.5, 0, 0}, {0, 0.9, 0}, "rug")
                              : Patch::make({0.2, 1.2, 0}, {0.5, 0, 0}, {0, -0.9, 0}, "rug"));
    scene.commit();
    const Link link{receiver, source, &scene};
    for (ExactOuterMethod outer : {ExactOuterMethod::criticalLines, ExactOuterMethod::genzMalik}) {
      SCOPED_TRACE(std::string(up ? "facing up, " : "facing down, ") + exactOuterMethodName(outer));
      ExactGoldOptions options;
      options.outer = outer;
      const ExactGold gold0 = exactGold(link, 0, options);
      EXPECT_TRUE(gold0.converged);
      EXPECT_NEAR(gold0.formFactor, analytic::parallelRectangles(1, 1, 1),
                  1e-9 + gold0.formFactorError);
      const ExactGold gold2 = exactGold(link, 2, options);
      EXPECT_TRUE(gold2.converged);
      const double largest = open2.coupling.cwiseAbs().maxCoeff();
      for (int a = 0; a < 9; ++a) {
        for (int b = 0; b < 9; ++b) {
          EXPECT_NEAR(gold2.coupling(a, b), open2.coupling(a, b),
                      gold2.couplingError(a, b) + open2.couplingError(a, b) + 1e-12 * largest)
              << a << ", " << b;
        }
      }
    }
  }
}

TEST(ExactGold, AWallStandingOnTheReceiverTakesTheCriticalLinesAndMatchesTheClosedForm) {
  // A wall standing on the receiver along x = 0.5, taller than the source is high: points on
  // its left see none of the source (which lies right of it), points on its right all of it.
  // The inner integral jumps along the wall's foot, where Genz-Malik converges slowly; the
  // critical lines take the foot as a breakpoint. With a floor limit that would send the
  // link to Genz-Malik, it still takes the lines, and F = 1/2 F(right half -> source).
  const Patch receiver = Patch::make({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, "receiver");
  const Patch source = Patch::make({0.5, 1, 1}, {1, 0, 0}, {0, -1, 0}, "source");
  ExactGoldOptions options;
  options.maxFloorPoints = 100;  // the jump raises it to 100 x 100 at 1e-7
  const std::vector<Eigen::Vector3d> half = {{0.5, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0.5, 1, 0}};
  const double expected = 0.5 * analytic::polygonToPolygonFormFactor(half, cornersOf(source));
  for (double foot : {0.0, 0.02}) {
    SCOPED_TRACE(foot);
    OccluderScene scene;
    scene.addParallelogram(Patch::make({0.5, -0.2, foot}, {0, 1.4, 0}, {0, 0, 1.5}, "wall"));
    scene.commit();
    const ExactGold gold = exactGold(Link{receiver, source, &scene}, 0, options);
    if (foot == 0.0) {
      EXPECT_EQ(gold.outer, ExactOuterMethod::criticalLines);
      EXPECT_TRUE(gold.converged);
      EXPECT_NEAR(gold.formFactor, expected, 1e-7 * expected + gold.formFactorError);
    } else {
      // Lifted off the receiver, the wall's shadow moves continuously: Genz-Malik.
      EXPECT_EQ(gold.outer, ExactOuterMethod::genzMalik);
    }
  }
}

TEST(ExactGold, ASlantedWallStandingOnTheReceiverTakesTheJumpLinesAndMatchesTheClosedForm) {
  // A tall wall standing on the receiver along the slanted line from (0.3, 0) to (0.7, 1), so
  // the jump crosses the lines and the starting grid at angles; the source lies right of the
  // wall's plane, so points left of the foot see none of it and points right of it all of it:
  // F = 1/2 F(right part -> source), the right part a trapezoid of area 1/2. With a floor
  // limit too small for the critical lines, the link takes the jump lines (not Genz-Malik,
  // whose estimate misjudges the jump); lifted off the receiver, the wall makes no jump and
  // the link takes Genz-Malik. Forced, the jump lines also meet a tight tolerance.
  const Patch receiver = Patch::make({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, "receiver");
  const Patch source = Patch::make({0.8, 1, 1}, {1, 0, 0}, {0, -1, 0}, "source");
  const std::vector<Eigen::Vector3d> right = {{0.3, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0.7, 1, 0}};
  const double expected = 0.5 * analytic::polygonToPolygonFormFactor(right, cornersOf(source));
  for (double foot : {0.0, 0.02}) {
    SCOPED_TRACE(foot);
    OccluderScene scene;
    scene.addParallelogram(Patch::make({0.1, -0.5, foot}, {0.8, 2.0, 0}, {0, 0, 1.5}, "wall"));
    scene.commit();
    const Link link{receiver, source, &scene};
    ExactGoldOptions options;
    options.tolerance = 1e-5;
    options.maxFloorPoints = 1;
    const ExactGold gold = exactGold(link, 0, options);
    if (foot == 0.0) {
      EXPECT_EQ(gold.outer, ExactOuterMethod::jumpLines);
      EXPECT_STREQ(exactOuterMethodName(gold.outer), "jump lines");
      EXPECT_TRUE(gold.converged);
      EXPECT_LE(gold.formFactorError, 1e-5 * gold.formFactor);
      EXPECT_NEAR(gold.formFactor, expected, gold.formFactorError);
      ExactGoldOptions tight;
      tight.outer = ExactOuterMethod::jumpLines;
      const ExactGold forced = exactGold(link, 0, tight);
      EXPECT_TRUE(forced.converged);
      EXPECT_NEAR(forced.formFactor, expected, 1e-7 * expected);
      EXPECT_NEAR(forced.formFactor, expected, forced.formFactorError);
    } else {
      EXPECT_EQ(gold.outer, ExactOuterMethod::genzMalik);
    }
  }
}

TEST(GoldReference, LinksWhoseKernelIsNotSmoothGoStraightToTheExactGold) {
  // Sharing an edge at right angles (singular along it), and a source cut by the receiver's
  // plane (the clamped cosine's discontinuity): the Gauss sequence would end unconverged at
  // 48^4 points; the gold skips it (no kernel evaluations) and integrates exactly.
  const Patch floor = Patch::make({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, "floor");
  const Patch wall = Patch::make({0, 0, 0}, {0, 0, 1}, {1, 0, 0}, "wall");
  const GoldReference touching = goldReference(Link{floor, wall, nullptr}, 0, 0);
  EXPECT_EQ(touching.method, "exact visibility");
  EXPECT_EQ(touching.kernelEvaluations, 0u);
  EXPECT_TRUE(touching.converged);
  const double expected = analytic::perpendicularRectangles(1, 1, 1);
  EXPECT_NEAR(touching.formFactor, expected, 2e-7 * expected);
  // A wall from z = -1 to z = 1 along the floor's far edge (y = 1), facing it: its lower half
  // lies behind the floor's plane, its upper half is the perpendicular pair above, so the
  // form factor (per unit receiver area) is the same.
  const Patch through = Patch::make({0, 1, -1}, {1, 0, 0}, {0, 0, 2}, "through");
  ASSERT_NEAR(through.normal.y(), -1.0, 1e-15);
  const GoldReference cut = goldReference(Link{floor, through, nullptr}, 0, 0);
  EXPECT_EQ(cut.method, "exact visibility");
  EXPECT_EQ(cut.kernelEvaluations, 0u);
  EXPECT_TRUE(cut.converged);
  EXPECT_NEAR(cut.formFactor, expected, 2e-7 * expected);
  // Apart from the floor (y = 2) and crossing its plane: not touching, cut by the receiver's
  // plane; the floor sees the upper half alone (the contour formula's value for it). With
  // the roles swapped the receiver crosses the source's plane, and by reciprocity its form
  // factor is the floor's times A_floor / A_wall = 1/2.
  const Patch apart = Patch::make({0, 2, -1}, {1, 0, 0}, {0, 0, 2}, "apart");
  ASSERT_GT(patchDistance(floor, apart), 0.5);
  const GoldReference cutApart = goldReference(Link{floor, apart, nullptr}, 0, 0);
  EXPECT_EQ(cutApart.method, "exact visibility");
  EXPECT_EQ(cutApart.kernelEvaluations, 0u);
  const Patch upperHalf = Patch::make({0, 2, 0}, {1, 0, 0}, {0, 0, 1}, "upper half");
  const double seen = analytic::polygonToPolygonFormFactor(cornersOf(floor), cornersOf(upperHalf));
  EXPECT_NEAR(cutApart.formFactor, seen, 1e-7 * seen);
  const GoldReference crossing = goldReference(Link{apart, floor, nullptr}, 0, 0);
  EXPECT_EQ(crossing.method, "exact visibility");
  EXPECT_EQ(crossing.kernelEvaluations, 0u);
  EXPECT_NEAR(crossing.formFactor, 0.5 * seen, 1e-7 * seen);
  // A smooth link keeps the Gauss sequence.
  const Patch facing = Patch::make({0, 1, 1}, {1, 0, 0}, {0, -1, 0}, "facing");
  EXPECT_EQ(goldReference(Link{floor, facing, nullptr}, 0, 0).method, "gauss product");
}

TEST(ExactGold, SkewPolygonsMatchTheContourFormula) {
  // A tilted, rotated pair, against the double contour integral of ln r (an independent
  // closed-form method: no area integration).
  const Patch receiver = Patch::make({0, 0, 0}, {1.2, 0.1, 0}, {-0.2, 0.8, 0.1}, "receiver");
  const Patch source = Patch::make({0.3, 1.1, 0.9}, {0.6, 0.2, 0.3}, {0.1, -0.9, 0.2}, "source");
  ASSERT_GT(source.normal.dot(receiver.centre() - source.centre()), 0.0);
  ASSERT_GT(receiver.normal.dot(source.centre() - receiver.centre()), 0.0);
  const ExactGold gold = exactGold(Link{receiver, source, nullptr}, 0);
  const double expected =
      analytic::polygonToPolygonFormFactor(cornersOf(receiver), cornersOf(source));
  EXPECT_NEAR(gold.formFactor, expected, 1e-9 * expected);
}

TEST(ExactGold, HigherDegreesMatchTheConvergedGaussGoldOnAnUnoccludedLink) {
  const Patch receiver = Patch::make({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, "receiver");
  const Patch source = Patch::make({0.2, 1.3, 0.8}, {0.9, 0, 0.3}, {0, -1.1, 0}, "source");
  const Link link{receiver, source, nullptr};
  for (const int degree : {1, 2, 3}) {
    const GoldReference gauss = goldReference(link, degree, 0);
    ASSERT_EQ(gauss.method, "gauss product");
    ASSERT_TRUE(gauss.converged);
    const ExactGold exact = exactGold(link, degree);
    const double largest = gauss.coupling.cwiseAbs().maxCoeff();
    EXPECT_LT((exact.coupling - gauss.coupling).cwiseAbs().maxCoeff(), 1e-8 * largest)
        << "degree " << degree;
  }
}

TEST(ExactGold, ASymmetricHalfBlockerLeavesExactlyHalf) {
  // The blocker covers x < 0.5 everywhere between two opposed unit squares; by the mirror
  // symmetry x -> 1 - x, exactly half of the form factor is left, at every degree's K[0][0].
  OccluderScene scene;
  scene.addParallelogram(Patch::make({-0.2, -0.2, 0.5}, {0.7, 0, 0}, {0, 1.4, 0}, "blocker"));
  scene.commit();
  const Patch receiver = Patch::make({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, "receiver");
  const Patch source = Patch::make({0, 1, 1}, {1, 0, 0}, {0, -1, 0}, "source");
  const ExactGold gold = exactGold(Link{receiver, source, &scene}, 0);
  EXPECT_TRUE(gold.converged);
  EXPECT_NEAR(gold.formFactor, 0.5 * analytic::parallelRectangles(1, 1, 1), 1e-9);
}

}  // namespace
}  // namespace radquad
