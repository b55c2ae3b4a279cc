// LinkGeometry: a link as data becomes the occluder scene and the Link the kernel integrates.
#include <gtest/gtest.h>

#include "kernel/link_geometry.h"

namespace radquad {
namespace {

LinkGeometry opposedSquares() {
  LinkGeometry geometry;
  geometry.receiver = Patch::make({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, "receiver");
  geometry.source = Patch::make({0, 1, 2}, {1, 0, 0}, {0, -1, 0}, "source");
  return geometry;
}

TEST(LinkGeometry, NothingInTheWayBuildsNoScene) {
  const LinkGeometry geometry = opposedSquares();
  EXPECT_FALSE(geometry.hasOccluders());
  EXPECT_EQ(geometry.occluderScene(), nullptr);
  const BuiltLink built = geometry.build();
  EXPECT_EQ(built.scene, nullptr);
  EXPECT_EQ(built.link.occluders, nullptr);
  EXPECT_FALSE(built.link.hasOccluders());
  EXPECT_EQ(built.link.receiver.origin, geometry.receiver.origin);
  EXPECT_EQ(built.link.source.edgeV, geometry.source.edgeV);
}

TEST(LinkGeometry, TrianglesKeepTheirOwnVerticesAndBlockWithTheParallelograms) {
  LinkGeometry geometry = opposedSquares();
  // A triangle over the corner (0, 0) of the receiver, a parallelogram over the corner (1, 1).
  geometry.addTriangle({0, 0, 1}, {0.4, 0, 1}, {0, 0.4, 1});
  geometry.addTriangle({0, 0, 1.5}, {0.1, 0, 1.5}, {0, 0.1, 1.5});
  geometry.parallelograms.push_back(Patch::make({0.6, 0.6, 1}, {0.4, 0, 0}, {0, 0.4, 0}, "p"));
  ASSERT_EQ(geometry.vertices.size(), 6u);
  ASSERT_EQ(geometry.triangles.size(), 2u);
  EXPECT_EQ(geometry.triangles[1], (std::array<std::uint32_t, 3>{3, 4, 5}));
  EXPECT_EQ(geometry.vertices[4], Eigen::Vector3d(0.1, 0, 1.5));
  EXPECT_TRUE(geometry.hasOccluders());
  const BuiltLink built = geometry.build();
  ASSERT_NE(built.scene, nullptr);
  EXPECT_EQ(built.link.occluders, built.scene.get());
  EXPECT_EQ(built.scene->primitiveCount(), 3u);
  const OccluderScene& scene = *built.link.occluders;
  EXPECT_FALSE(scene.segmentVisible({0.1, 0.1, 0}, {0.1, 0.1, 2}));  // under the triangle
  EXPECT_FALSE(scene.segmentVisible({0.8, 0.8, 0}, {0.8, 0.8, 2}));  // under the parallelogram
  EXPECT_TRUE(scene.segmentVisible({0.5, 0.5, 0}, {0.5, 0.5, 2}));   // between the two
}

}  // namespace
}  // namespace radquad
