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

TEST(VisibilityTest, BackToBackPatchesDoNotExchange) {
  const Patch a = Patch::make(Vec::Zero(), Vec::UnitX(), Vec::UnitY(), "a");    // faces +z
  const Patch b = Patch::make(Vec(0, 0, -1), Vec::UnitX(), Vec::UnitY(), "b");  // faces +z
  EXPECT_FALSE(mayExchange(b, a));  // b faces a, but a faces away from b
  EXPECT_TRUE(mayExchange(a, Patch::make(Vec(0, 0, 1), Vec::UnitY(), Vec::UnitX(), "c")));
}

}  // namespace
}  // namespace radquad
