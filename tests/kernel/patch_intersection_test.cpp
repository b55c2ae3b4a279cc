// Interpenetrating patches (crossing or overlapping) against legal contact (a shared edge, a
// shared corner, an edge lying on the other patch), and the kernel paths on points that
// coincide: no NaN, and ray buffers filled with the same predicate they were sized with.
#include <gtest/gtest.h>

#include <cmath>

#include "quadrature/rule.h"
#include "kernel/coupling.h"
#include "kernel/legendre_basis.h"
#include "kernel/patch_intersection.h"
#include "quadrature/registry.h"

namespace radquad {
namespace {

Patch square(const Eigen::Vector3d& o, const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return Patch::make(o, a, b, "p");
}

TEST(PatchIntersection, CrossingPatchesAreReportedWithTheSegmentLength) {
  const Patch floor = square({0, 0, 0}, {1, 0, 0}, {0, 1, 0});
  // A vertical wall through the middle of the floor, 1 below to 1 above: they share the
  // segment x = 0.5, y in [0, 1] (length 1).
  const Patch wall = square({0.5, 0, -1}, {0, 1, 0}, {0, 0, 2});
  const auto crossing = patchesInterpenetrate(floor, wall);
  ASSERT_TRUE(crossing.has_value());
  EXPECT_NE(crossing->find("segment of length 1"), std::string::npos) << *crossing;
  EXPECT_TRUE(patchesInterpenetrate(wall, floor).has_value());
  // The input of the reported memory fault: a tilted receiver through a source.
  const Patch receiver = square({0, 0, 0}, {1, 0, 2}, {0, 1, 0});
  const Patch source = square({0, 1, 1}, {1, 0, 0}, {0, -1, 0});
  EXPECT_TRUE(patchesInterpenetrate(receiver, source).has_value());
}

TEST(PatchIntersection, CoincidentAndOverlappingCoplanarPatches) {
  const Patch a = square({0, 0, 0}, {1, 0, 0}, {0, 1, 0});
  const auto same = patchesInterpenetrate(a, a);
  ASSERT_TRUE(same.has_value());
  EXPECT_NE(same->find("area of 1"), std::string::npos) << *same;
  // Opposite orientation, shifted by a quarter: overlap 0.75 x 1.
  const Patch flipped = square({0.25, 0, 0}, {0, 1, 0}, {1, 0, 0});
  const auto overlap = patchesInterpenetrate(a, flipped);
  ASSERT_TRUE(overlap.has_value());
  EXPECT_NE(overlap->find("area of 0.75"), std::string::npos) << *overlap;
}

TEST(PatchIntersection, TouchingIsLegal) {
  const Patch floor = square({0, 0, 0}, {1, 0, 0}, {0, 1, 0});
  // Shared edge at a right angle, coplanar neighbours, a shared corner.
  EXPECT_FALSE(patchesInterpenetrate(floor, square({0, 0, 0}, {0, 0, 1}, {1, 0, 0})));
  EXPECT_FALSE(patchesInterpenetrate(floor, square({1, 0, 0}, {1, 0, 0}, {0, 1, 0})));
  EXPECT_FALSE(patchesInterpenetrate(floor, square({1, 1, 0}, {0, 0, 1}, {1, 0, 0})));
  // A block face standing on the floor's interior: its bottom edge lies on the floor.
  EXPECT_FALSE(patchesInterpenetrate(floor, square({0.5, 0.2, 0}, {0, 0.5, 0}, {0, 0, 1})));
  // Parallel and apart, and a wall beside the floor that does not reach it.
  EXPECT_FALSE(patchesInterpenetrate(floor, square({0, 0, 1}, {1, 0, 0}, {0, 1, 0})));
  EXPECT_FALSE(patchesInterpenetrate(floor, square({2, 0, -1}, {0, 1, 0}, {0, 0, 2})));
}

TEST(PatchDistance, ClosedFormsOfSimpleConfigurations) {
  const Patch floor = square({0, 0, 0}, {1, 0, 0}, {0, 1, 0});
  // Parallel and opposed at 0.3; shifted sideways by 2 (closest: edge to edge, sqrt(1 + 0.09)).
  EXPECT_NEAR(patchDistance(floor, square({0, 0, 0.3}, {0, 1, 0}, {1, 0, 0})), 0.3, 1e-12);
  EXPECT_NEAR(patchDistance(floor, square({2, 0, 0.3}, {0, 1, 0}, {1, 0, 0})), std::sqrt(1.09),
              1e-12);
  // A wall standing 0.2 beyond the floor's edge x = 1, from z = 0.5 up: corner to edge.
  EXPECT_NEAR(patchDistance(floor, square({1.2, 0, 0.5}, {0, 1, 0}, {0, 0, 1})),
              std::sqrt(0.04 + 0.25), 1e-12);
  // Touching along an edge, and crossing.
  EXPECT_EQ(patchDistance(floor, square({0, 0, 0}, {0, 0, 1}, {1, 0, 0})), 0.0);
  EXPECT_EQ(patchDistance(floor, square({0.5, 0, -1}, {0, 1, 0}, {0, 0, 2})), 0.0);
  // Nearness is relative to the smaller patch's shorter side (0.5 x 0.25 here).
  EXPECT_NEAR(nearnessRatio(floor, square({0, 0, 0.05}, {0, 0.25, 0}, {0.5, 0, 0})), 0.2, 1e-12);
}

TEST(CoincidentPoints, TheKernelIsZeroNotNaN) {
  const Patch p = square({0, 0, 0}, {1, 0, 0}, {0, 1, 0});
  EXPECT_EQ(unoccludedKernel(p, {0.5, 0.5, 0}, p, {0.5, 0.5, 0}), 0.0);
}

// Crossing patches share points where the kernel was 0/0; with occluders, the product path
// sized its rays by counting positive kernels and filled them skipping non-positive ones, so
// a NaN overflowed the buffer. Every path must give a finite coupling on such a link (the
// input layer rejects it, but the kernel must not corrupt memory on it).
TEST(CoincidentPoints, EveryPathStaysFiniteOnCrossingPatches) {
  const Patch receiver = square({0, 0, 0}, {1, 0, 2}, {0, 1, 0});
  const Patch source = square({0, 1, 1}, {1, 0, 0}, {0, -1, 0});
  OccluderScene scene;
  scene.addParallelogram(square({-1, -1, 0.5}, {1.5, 0, 0}, {0, 3, 0}));
  scene.commit();
  const Link link{receiver, source, &scene};
  CouplingAccumulator accumulator;
  const RuleSamples samples = findRule("FullGauss")->samples(0);
  for (int degree = 0; degree <= 3; ++degree) {
    const WeightedBasisTable rb = makeWeightedBasisTable(samples.receiver, degree);
    const WeightedBasisTable sb = makeWeightedBasisTable(samples.source, degree);
    LinkIntegral product, scattered;
    accumulator.product(link, samples.receiver, rb, samples.source, sb, product);
    accumulator.scattered(link, flattenedPoints(samples), degree, scattered);
    EXPECT_TRUE(product.coupling.allFinite()) << "degree " << degree;
    EXPECT_TRUE(scattered.coupling.allFinite()) << "degree " << degree;
    EXPECT_LE(product.raysCast, samples.receiver.size() * samples.source.size());
    EXPECT_EQ(product.raysCast, scattered.raysCast);
  }
}

TEST(PolygonCrossesPatch, OnlyAPolygonThroughThePatchsInteriorCrossesIt) {
  const Patch floor = Patch::make({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, "floor");
  const std::vector<Eigen::Vector3d> through = {
      {0.2, 0.5, -0.3}, {0.8, 0.5, -0.3}, {0.8, 0.5, 0.3}, {0.2, 0.5, 0.3}};
  EXPECT_TRUE(polygonCrossesPatch(through, floor));
  // The same wall beside the floor crosses its plane, not the floor.
  std::vector<Eigen::Vector3d> beside = through;
  for (auto& p : beside) p.y() += 1.2;
  EXPECT_FALSE(polygonCrossesPatch(beside, floor));
  // Standing on the floor (an edge on it) or touching it with a vertex is not crossing.
  const std::vector<Eigen::Vector3d> standing = {
      {0.2, 0.5, 0.0}, {0.8, 0.5, 0.0}, {0.8, 0.5, 0.6}, {0.2, 0.5, 0.6}};
  EXPECT_FALSE(polygonCrossesPatch(standing, floor));
  const std::vector<Eigen::Vector3d> corner = {{0.5, 0.5, 0.0}, {0.9, 0.5, 0.4}, {0.1, 0.5, 0.4}};
  EXPECT_FALSE(polygonCrossesPatch(corner, floor));
  // A tilted triangle whose cut just clips the floor's corner region crosses it.
  const std::vector<Eigen::Vector3d> clipping = {{-0.5, 0.1, -0.2}, {0.1, -0.5, -0.2}, {0.5, 0.5, 0.3}};
  EXPECT_TRUE(polygonCrossesPatch(clipping, floor));
}

}  // namespace
}  // namespace radquad
