// Link classification: conservative (a blocker in the way is never missed), and exact on
// clear cases.
#include <gtest/gtest.h>

#include "kernel/occluder_scene.h"
#include "radiosity/visibility.h"
#include "tests/radiosity/scenes_for_tests.h"

namespace radquad {
namespace {

using Vec = Eigen::Vector3d;

struct ClassifierScene {
  Scene scene;
  OccluderScene occluders;
  explicit ClassifierScene(Scene s) : scene(std::move(s)) {
    for (const ScenePatch& p : scene.patches) occluders.addParallelogram(p.patch);
    occluders.commit();
  }
};

Scene squaresWith(const std::vector<Patch>& blockers) {
  Scene scene = testing::opposedSquaresScene(0.5);
  for (const Patch& blocker : blockers) {
    scene.patches.push_back(ScenePatch{"blocker", blocker, Vec::Constant(0.5), Vec::Zero()});
  }
  return scene;
}

Classification classifySquares(const ClassifierScene& setup) {
  const VisibilityClassifier classifier(setup.scene, setup.occluders);
  return classifier.classify(setup.scene.patches[1].patch, 1, setup.scene.patches[0].patch, 0,
                             nullptr);
}

TEST(VisibilityTest, NothingInTheShaftIsUnoccluded) {
  // A blocker beside the shaft (x in [2,3]) and one behind the emitter.
  const ClassifierScene setup(
      squaresWith({Patch::make(Vec(2, 0, 0.5), Vec(1, 0, 0), Vec(0, 1, 0), "beside"),
                   Patch::make(Vec(0, 0, -1), Vec(1, 0, 0), Vec(0, 1, 0), "behind")}));
  const Classification result = classifySquares(setup);
  EXPECT_EQ(result.visibility, LinkClass::kUnoccluded);
  EXPECT_TRUE(result.candidates.empty());
}

TEST(VisibilityTest, SmallBlockerInTheMiddleIsPartial) {
  const ClassifierScene setup(
      squaresWith({Patch::make(Vec(0.4, 0.4, 0.5), Vec(0.2, 0, 0), Vec(0, 0.2, 0), "middle")}));
  const Classification result = classifySquares(setup);
  EXPECT_EQ(result.visibility, LinkClass::kPartial);
  ASSERT_EQ(result.candidates.size(), 1u);
  EXPECT_EQ(result.candidates[0], 2);
}

TEST(VisibilityTest, TinyBlockerMissedByEveryRayIsStillNotUnoccluded) {
  // Smaller than the ray grid's spacing and off its rays: rays see nothing, the shaft test
  // still finds it, so the link must be partial.
  const ClassifierScene setup(squaresWith(
      {Patch::make(Vec(0.01, 0.01, 0.5), Vec(0.005, 0, 0), Vec(0, 0.005, 0), "speck")}));
  EXPECT_EQ(classifySquares(setup).visibility, LinkClass::kPartial);
}

TEST(VisibilityTest, WallBetweenIsOccluded) {
  const ClassifierScene setup(
      squaresWith({Patch::make(Vec(-1, -1, 0.5), Vec(3, 0, 0), Vec(0, 3, 0), "wall")}));
  EXPECT_EQ(classifySquares(setup).visibility, LinkClass::kOccluded);
}

TEST(VisibilityTest, AWallCoveringTheShaftProvesTheOcclusion) {
  const ClassifierScene setup(
      squaresWith({Patch::make(Vec(-1, -1, 0.5), Vec(3, 0, 0), Vec(0, 3, 0), "wall")}));
  const Classification result = classifySquares(setup);
  EXPECT_EQ(result.visibility, LinkClass::kOccluded);
  EXPECT_TRUE(result.occlusionProven);
}

// Two walls that meet in the middle of the shaft block every grid ray between them, but
// neither covers the shaft alone: occluded by the rays, not proven (the solver keeps
// examining such links). A slit between the walls narrower than the rays' spacing is the
// case the proof guards against: every ray blocked, yet energy passes.
TEST(VisibilityTest, RaysAloneDoNotProveAnOcclusion) {
  const double slit = 0.01;
  const ClassifierScene setup(
      squaresWith({Patch::make(Vec(-1, -1, 0.5), Vec(1.5 + 0.03, 0, 0), Vec(0, 3, 0), "left"),
                   Patch::make(Vec(0.53 + slit, -1, 0.5), Vec(1.5, 0, 0), Vec(0, 3, 0), "right")}));
  const Classification result = classifySquares(setup);
  EXPECT_EQ(result.visibility, LinkClass::kOccluded);
  EXPECT_FALSE(result.occlusionProven);
}

// blocksShaft against the geometry: the 16 corner segments decide, and the plane must
// separate the elements.
TEST(VisibilityTest, BlocksShaftIsExactOnTheCornerSegments) {
  const Patch receiver = Patch::make(Vec(0, 0, 1), Vec(0, 1, 0), Vec(1, 0, 0), "receiver");
  const Patch source = Patch::make(Vec(0, 0, 0), Vec(1, 0, 0), Vec(0, 1, 0), "source");
  // At the mid plane the shaft's section is the unit square: a blocker just larger covers it,
  // one just smaller (by 1e-3 on one side) does not.
  EXPECT_TRUE(blocksShaft(Patch::make(Vec(-1e-3, -1e-3, 0.5), Vec(1.002, 0, 0), Vec(0, 1.002, 0), "b"),
                          receiver, source));
  EXPECT_FALSE(blocksShaft(Patch::make(Vec(1e-3, -1e-3, 0.5), Vec(1.0, 0, 0), Vec(0, 1.002, 0), "b"),
                           receiver, source));
  // A larger source widens the section: near the source the blocker must be as wide.
  const Patch wide = Patch::make(Vec(-1, -1, 0), Vec(3, 0, 0), Vec(0, 3, 0), "wide");
  EXPECT_FALSE(blocksShaft(Patch::make(Vec(-0.5, -0.5, 0.25), Vec(2, 0, 0), Vec(0, 2, 0), "b"),
                           receiver, wide));
  EXPECT_TRUE(blocksShaft(Patch::make(Vec(-0.8, -0.8, 0.25), Vec(2.6, 0, 0), Vec(0, 2.6, 0), "b"),
                          receiver, wide));
  // A plane that cuts an element does not separate them.
  EXPECT_FALSE(blocksShaft(Patch::make(Vec(-5, -5, 0), Vec(10, 0, 0), Vec(0, 10, 0), "b"),
                           receiver, source));
}

// A wall element straddling the outline of a plate hung just in front of it, and a large floor
// far away: the visibility changes across the wall element (its lower part, z < 1.4, is behind the plate),
// not across the floor, so refinement must split the wall element (Solver::splitSide).
TEST(VisibilityTest, VariationFindsTheElementThatHoldsTheShadowBoundary) {
  Scene scene;
  const Patch wall = Patch::make(Vec(0, 1, 1), Vec(0, 1, 0), Vec(0, 0, 1), "wall element");
  const Patch floor = Patch::make(Vec(0.5, 0, 0), Vec(0, 0, 4), Vec(4, 0, 0), "floor");
  const Patch plate = Patch::make(Vec(0.003, 0, 0), Vec(0, 5, 0), Vec(0, 0, 1.4), "plate");
  ASSERT_GT(wall.normal.x(), 0.0);
  ASSERT_GT(floor.normal.y(), 0.0);
  for (const Patch& p : {wall, floor, plate}) {
    scene.patches.push_back(ScenePatch{"p", p, Vec::Constant(0.5), Vec::Zero()});
  }
  const ClassifierScene setup(scene);
  const VisibilityVariation variation = visibilityVariation(setup.occluders, wall, floor);
  EXPECT_TRUE(variation.receiver);
  EXPECT_FALSE(variation.source);
  // Seen the other way round, the floor receiving from the wall element.
  const VisibilityVariation reversed = visibilityVariation(setup.occluders, floor, wall);
  EXPECT_FALSE(reversed.receiver);
  EXPECT_TRUE(reversed.source);
}

TEST(VisibilityTest, OneVisibleGridRayMakesThePartialClass) {
  // A wall at z = 0.5 with a small hole where exactly one grid ray crosses: the ray from
  // the receiver's grid point (u, v) = (0.875, 0.125) to the emitter's (0.125, 0.875), both
  // at (x, y) = (0.125, 0.875); no other pair's midpoint is there. The classifier may stop
  // at the first visible ray, so whatever its order it must find this one.
  const Vec from = Vec::UnitZ() + 0.875 * Vec::UnitY() + 0.125 * Vec::UnitX();  // receiver
  const Vec to = 0.125 * Vec::UnitX() + 0.875 * Vec::UnitY();                    // emitter
  const Vec hole = 0.5 * (from + to);
  const double half = 0.01;
  const double lo = -1, hi = 2;
  const Vec ex = Vec::UnitX(), ey = Vec::UnitY();
  const ClassifierScene setup(squaresWith({
      Patch::make(Vec(lo, lo, 0.5), (hi - lo) * ex, (hole.y() - half - lo) * ey, "below"),
      Patch::make(Vec(lo, hole.y() + half, 0.5), (hi - lo) * ex, (hi - hole.y() - half) * ey,
                  "above"),
      Patch::make(Vec(lo, hole.y() - half, 0.5), (hole.x() - half - lo) * ex, 2 * half * ey,
                  "left"),
      Patch::make(Vec(hole.x() + half, hole.y() - half, 0.5), (hi - hole.x() - half) * ex,
                  2 * half * ey, "right")}));
  // Independent check that the hole passes this ray and no other of the 16 x 16 grid pairs.
  int through = 0;
  for (int i = 0; i < 16; ++i) {
    for (int j = 0; j < 16; ++j) {
      const Vec a = setup.scene.patches[1].patch.pointAt((i / 4 + 0.5) / 4, (i % 4 + 0.5) / 4);
      const Vec b = setup.scene.patches[0].patch.pointAt((j / 4 + 0.5) / 4, (j % 4 + 0.5) / 4);
      if (setup.occluders.segmentVisible(a, b)) ++through;
    }
  }
  ASSERT_EQ(through, 1);
  const Classification result = classifySquares(setup);
  EXPECT_EQ(result.visibility, LinkClass::kPartial);
  EXPECT_EQ(result.candidates.size(), 4u);
}

TEST(VisibilityTest, OnlyAnUnprovenOcclusionTracesEveryPair) {
  // Opposed squares: all 256 pairs face each other. A full wall covers the shaft: proven
  // occluded by the geometry, with no ray cast. Two walls with a slit narrower than the rays'
  // spacing block every ray but prove nothing: every pair is traced before the link is called
  // occluded. A speck blocks none, and the first packet of 16 already shows a visible ray.
  const ClassifierScene wall(
      squaresWith({Patch::make(Vec(-1, -1, 0.5), Vec(3, 0, 0), Vec(0, 3, 0), "wall")}));
  const Classification covered = classifySquares(wall);
  EXPECT_EQ(covered.visibility, LinkClass::kOccluded);
  EXPECT_TRUE(covered.occlusionProven);
  EXPECT_EQ(covered.raysCast, 0u);
  const ClassifierScene slit(
      squaresWith({Patch::make(Vec(-1, -1, 0.5), Vec(1.53, 0, 0), Vec(0, 3, 0), "left"),
                   Patch::make(Vec(0.54, -1, 0.5), Vec(1.5, 0, 0), Vec(0, 3, 0), "right")}));
  const Classification blocked = classifySquares(slit);
  EXPECT_EQ(blocked.visibility, LinkClass::kOccluded);
  EXPECT_FALSE(blocked.occlusionProven);
  EXPECT_EQ(blocked.raysCast, 256u);
  const ClassifierScene speck(squaresWith(
      {Patch::make(Vec(0.01, 0.01, 0.5), Vec(0.005, 0, 0), Vec(0, 0.005, 0), "speck")}));
  const Classification open = classifySquares(speck);
  EXPECT_EQ(open.visibility, LinkClass::kPartial);
  EXPECT_EQ(open.raysCast, 16u);
}

TEST(VisibilityTest, PairsWithAPointBehindTheOtherPlaneAreNotTraced) {
  // The receiver lies on the floor (z = 0, facing up); the source stands in the plane x = 2
  // facing it and reaches below the floor (z from -0.5 to 1.5): its grid row at z = -0.25
  // is behind the receiver's plane, so 16 x 12 = 192 pairs carry a positive kernel. Two walls
  // at x = 1.5 leave a slit at z in (0.010, 0.011), which the rays cross at z >= 0.139: every
  // ray is blocked, nothing proves it, and the occluded class traces exactly those 192 pairs.
  Scene scene;
  scene.patches.push_back(ScenePatch{
      "source", Patch::make(Vec(2, 0, -0.5), Vec(0, 0, 2), Vec(0, 1, 0), "source"),
      Vec::Constant(0.5), Vec::Zero()});
  scene.patches.push_back(ScenePatch{
      "receiver", Patch::make(Vec(0, 0, 0), Vec(1, 0, 0), Vec(0, 1, 0), "receiver"),
      Vec::Constant(0.5), Vec::Zero()});
  ASSERT_LT(scene.patches[0].patch.normal.x(), 0.0);
  ASSERT_GT(scene.patches[1].patch.normal.z(), 0.0);
  for (const auto& [low, high] : {std::pair{-1.0, 0.010}, std::pair{0.011, 3.0}}) {
    scene.patches.push_back(ScenePatch{
        "wall", Patch::make(Vec(1.5, -1, low), Vec(0, 3, 0), Vec(0, 0, high - low), "wall"),
        Vec::Constant(0.5), Vec::Zero()});
  }
  const ClassifierScene setup(std::move(scene));
  int facing = 0;
  for (int i = 0; i < 16; ++i) {
    for (int j = 0; j < 16; ++j) {
      const Vec y = setup.scene.patches[0].patch.pointAt((j / 4 + 0.5) / 4, (j % 4 + 0.5) / 4);
      if (y.z() > 0.0) ++facing;
    }
  }
  ASSERT_EQ(facing, 192);
  const Classification result = classifySquares(setup);
  EXPECT_EQ(result.visibility, LinkClass::kOccluded);
  EXPECT_FALSE(result.occlusionProven);
  EXPECT_EQ(result.raysCast, 192u);
}

TEST(VisibilityTest, BackToBackPatchesDoNotExchange) {
  const Patch a = Patch::make(Vec::Zero(), Vec::UnitX(), Vec::UnitY(), "a");    // faces +z
  const Patch b = Patch::make(Vec(0, 0, -1), Vec::UnitX(), Vec::UnitY(), "b");  // faces +z
  EXPECT_FALSE(mayExchange(b, a));  // b faces a, but a faces away from b
  EXPECT_TRUE(mayExchange(a, Patch::make(Vec(0, 0, 1), Vec::UnitY(), Vec::UnitX(), "c")));
}

}  // namespace
}  // namespace radquad
