// Visibility: Embree occlusion against parallelograms and triangle meshes, and its effect on
// the coupling (fully blocked links, a half-blocked link whose answer follows from symmetry).
#include <gtest/gtest.h>

#include "kernel/coupling.h"
#include "kernel/occluder_scene.h"
#include "quadrature/prepared_rule.h"
#include "quadrature/registry.h"
#include "tests/kernel/test_links.h"

namespace radquad {
namespace {

using testing::opposedReceiver;
using testing::opposedSource;

TEST(OccluderScene, ParallelogramBlocksCrossingSegmentsOnly) {
  OccluderScene scene;
  scene.addParallelogram(Patch::make({0, 0, 1}, {1, 0, 0}, {0, 1, 0}, "blocker"));
  scene.commit();
  EXPECT_FALSE(scene.segmentVisible({0.5, 0.5, 0}, {0.5, 0.5, 2}));   // through the middle
  EXPECT_TRUE(scene.segmentVisible({1.5, 0.5, 0}, {1.5, 0.5, 2}));    // beside it
  EXPECT_TRUE(scene.segmentVisible({0.5, 0.5, 0}, {0.5, 0.5, 0.9}));  // stops short
  EXPECT_FALSE(scene.segmentVisible({0.5, 0.5, 2}, {0.5, 0.5, 0}));   // both sides block
  // A segment ending on the occluder's surface is not blocked by it (end-point epsilon).
  EXPECT_TRUE(scene.segmentVisible({0.5, 0.5, 0}, {0.5, 0.5, 1}));
}

TEST(OccluderScene, TriangleMeshBlocks) {
  OccluderScene scene;
  scene.addTriangleMesh({{0, 0, 1}, {1, 0, 1}, {0, 1, 1}}, {{0, 1, 2}});
  scene.commit();
  EXPECT_EQ(scene.primitiveCount(), 1u);
  EXPECT_FALSE(scene.segmentVisible({0.2, 0.2, 0}, {0.2, 0.2, 2}));
  EXPECT_TRUE(scene.segmentVisible({0.8, 0.8, 0}, {0.8, 0.8, 2}));  // beyond the hypotenuse
  OccluderScene fresh;
  EXPECT_THROW(fresh.addTriangleMesh({{0, 0, 0}}, {{0, 1, 2}}), std::invalid_argument);
  // Adding to a committed scene is a bug, caught in every build.
  EXPECT_THROW(scene.addTriangleMesh({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {{0, 1, 2}}),
               std::logic_error);
}

TEST(OccluderScene, PacketsOfManySegmentsMatchSingleTests) {
  OccluderScene scene;
  scene.addParallelogram(Patch::make({0, 0, 1}, {0.5, 0, 0}, {0, 1, 0}, "half"));
  scene.commit();
  SegmentBatch batch;
  std::vector<bool> expected;
  for (int k = 0; k < 37; ++k) {  // not a multiple of the packet width
    const double x = (k + 0.5) / 37.0;
    batch.push({x, 0.5, 0}, {0, 0, 2});
    expected.push_back(x > 0.5);
  }
  std::vector<std::uint8_t> visible(batch.size());
  scene.testSegments(batch, visible.data());
  for (int k = 0; k < 37; ++k) EXPECT_EQ(bool(visible[k]), expected[k]) << "segment " << k;
}

TEST(Visibility, FullyBlockedLinkIsExactlyZero) {
  OccluderScene scene;
  scene.addParallelogram(Patch::make({-1, -1, 0.5}, {3, 0, 0}, {0, 3, 0}, "wall"));
  scene.commit();
  const Link link{opposedReceiver(1, 1), opposedSource(1, 1, 1), &scene};
  for (const char* rule : {"FullGauss", "ConstSrcGauss", "Gauss:5x4x3x2"}) {
    const auto integral = PreparedRule(findRule(rule), 2).integrate(link);
    EXPECT_EQ(integral.coupling.cwiseAbs().maxCoeff(), 0.0) << rule;
    EXPECT_EQ(integral.formFactor, 0.0) << rule;
    EXPECT_EQ(integral.visibleFraction(), 0.0) << rule;
    EXPECT_EQ(integral.raysCast, integral.kernelEvaluations) << rule;
  }
}

// Opposed unit squares at distance 1 with a blocker covering x < 1/2 of the mid plane. The
// reflection x -> 1 - x maps the blocked pairs (midpoint x < 1/2) onto the visible ones and
// keeps G, so exactly half of the form factor gets through. A product rule whose receiver and
// source nodes are symmetric about 1/2 but never sum to 1 along x (4 and 3 Gauss points) has
// the same property exactly, with no ray grazing the blocker's edge.
TEST(Visibility, SymmetricHalfBlockedLinkPassesHalf) {
  OccluderScene scene;
  scene.addParallelogram(Patch::make({-1, -1, 0.5}, {1.5, 0, 0}, {0, 3, 0}, "half wall"));
  scene.commit();
  const Link open{opposedReceiver(1, 1), opposedSource(1, 1, 1), nullptr};
  const Link half{open.receiver, open.source, &scene};
  const PreparedRule rule(findRule("Gauss:4x4x3x3"), 0);
  const auto unoccluded = rule.integrate(open);
  const auto blocked = rule.integrate(half);
  EXPECT_EQ(blocked.visibleFraction(), 0.5);
  EXPECT_NEAR(blocked.formFactor, 0.5 * unoccluded.formFactor, 1e-15);
}

}  // namespace
}  // namespace radquad
