// The exact visibility (reference/exact_visibility.h) where rings and occluders touch:
// convex rings that overlap, touch or hold one another, repeated vertices, an occluder vertex
// on a pyramid's plane, a shared edge and an occluder lying on the source, in any frame.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "kernel/occluder_scene.h"
#include "reference/exact_visibility.h"
#include "reference/source_moments.h"
#include "tests/reference/halfway_occluders.h"

namespace radquad {
namespace {

// A random rotation (a normalized quaternion of four normal draws) and a shift of up to 1.5 on
// each axis (three uniform draws), drawn in that order.
struct RigidMotion {
  Eigen::Matrix3d turn = Eigen::Matrix3d::Identity();
  Eigen::Vector3d shift = Eigen::Vector3d::Zero();

  Eigen::Vector3d point(const Eigen::Vector3d& p) const { return turn * p + shift; }
  Patch patch(const Eigen::Vector3d& origin, const Eigen::Vector3d& edgeU,
              const Eigen::Vector3d& edgeV, const char* name) const {
    return Patch::make(point(origin), turn * edgeU, turn * edgeV, name);
  }
  Patch patch(const Patch& p, const char* name) const {
    return patch(p.origin, p.edgeU, p.edgeV, name);
  }
};

RigidMotion randomMotion(std::mt19937_64& random, std::normal_distribution<double>& normal,
                         std::uniform_real_distribution<double>& unit) {
  Eigen::Quaterniond q(normal(random), normal(random), normal(random), normal(random));
  q.normalize();
  RigidMotion motion;
  motion.turn = q.toRotationMatrix();
  motion.shift = {3 * unit(random) - 1.5, 3 * unit(random) - 1.5, 3 * unit(random) - 1.5};
  return motion;
}

TEST(ExactVisibility, ConvexRingsIntersectAsTheirShapesDo) {
  // Overlapping squares give their common square; a ring inside another gives itself; rings
  // that only touch or lie apart give nothing with area.
  const SourceRing square = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  const SourceRing shifted = {{0.5, 0.25}, {1.5, 0.25}, {1.5, 1.25}, {0.5, 1.25}};
  const SourceRing inner = {{0.2, 0.2}, {0.6, 0.3}, {0.4, 0.7}};
  const SourceRing touching = {{1, 0}, {2, 0}, {2, 1}, {1, 1}};
  const SourceRing apart = {{2, 0}, {3, 0}, {3, 1}, {2, 1}};
  SourceRing out, scratch;
  intersectConvexRings(square, shifted, out, scratch);
  EXPECT_NEAR(ringArea(out), 0.5 * 0.75, 1e-15);
  intersectConvexRings(shifted, square, out, scratch);
  EXPECT_NEAR(ringArea(out), 0.5 * 0.75, 1e-15);
  intersectConvexRings(square, inner, out, scratch);
  EXPECT_NEAR(ringArea(out), ringArea(inner), 1e-15);
  intersectConvexRings(square, touching, out, scratch);
  EXPECT_FALSE(out.size() >= 3 && ringArea(out) > 0.0);
  intersectConvexRings(square, apart, out, scratch);
  EXPECT_LT(out.size(), 3u);
}

TEST(ExactVisibility, OccluderVertexOnAPyramidPlaneIsSubtractedOnce) {
  // Occluder a has a vertex exactly on the pyramid plane through x and the source's edge
  // X = 0, and the next vertex outside it: the clip repeats that vertex, and a's shadow ring
  // has an edge of length zero. Such an edge is no separating axis: a's shadow lies inside
  // b's, which overlaps d's, so the visible form factor is the source's minus b's and d's
  // shadows (a hides nothing that b does not).
  OccluderScene scene;
  scene.addParallelogram(Patch::make({0.25, 0.36, 0.5}, {-0.05, 0.03, 0}, {0.10, 0.03, 0}, "a"));
  scene.addParallelogram(Patch::make({0.25, 0.30, 0.5}, {0.15, 0, 0}, {0, 0.15, 0}, "b"));
  scene.addParallelogram(Patch::make({0.35, 0.40, 0.5}, {0.10, 0, 0}, {0, 0.10, 0}, "d"));
  scene.commit();
  const HalfwaySetup setup;
  const double expected = setup.toSource() - setup.toRectangle(0.0, 0.3, 0.1, 0.4) -
                          setup.toRectangle(0.2, 0.4, 0.3, 0.5) +
                          setup.toRectangle(0.2, 0.3, 0.3, 0.4);
  std::size_t unions = 0, rings = 0;
  for (ShadowUnion method :
       {ShadowUnion::inclusionExclusion, ShadowUnion::clipper, ShadowUnion::outline}) {
    EXPECT_NEAR(setup.visibleFormFactor(scene, unions, rings, method), expected, 1e-12)
        << int(method);
    EXPECT_EQ(unions, 1u);
  }
}

TEST(ExactVisibility, RingsWithRepeatedVerticesOverlapAsTheirShapesDo) {
  // A zero edge, and one of a few units in the last place (what the clip leaves), must not
  // serve as a separating axis; the rings' real edges still separate disjoint ones.
  const SourceRing square = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  const SourceRing repeated = {{0.5, 0.5}, {1.5, 0.5}, {1.5, 0.5}, {1.5, 1.5}, {0.5, 1.5}};
  const SourceRing nearlyRepeated = {
      {0.5, 0.5}, {1.5, 0.5}, {1.5 + 4e-16, 0.5 - 2e-16}, {1.5, 1.5}, {0.5, 1.5}};
  const SourceRing apart = {{2, 0}, {3, 0}, {3, 0}, {3, 1}, {2, 1}};
  for (const SourceRing* ring : {&repeated, &nearlyRepeated}) {
    EXPECT_TRUE(convexRingsOverlap(square, *ring));
    EXPECT_TRUE(convexRingsOverlap(*ring, square));
  }
  EXPECT_FALSE(convexRingsOverlap(square, apart));
  EXPECT_FALSE(convexRingsOverlap(apart, square));
}

TEST(ExactVisibility, ASharedEdgeGivesTheSameVisibleIntegralsInAnyFrame) {
  // A floor receiver and a wall source meeting along an edge, a box face standing on the
  // floor, its top, and a shelf touching the wall. In the frame of the axes the source's
  // corners on the shared edge lie exactly on every receiver point's tangent plane; turned
  // and moved, they lie on it up to rounding, and the clip of the source leaves a corner
  // twice, an ulp apart. The visible integrals do not depend on the frame: at degrees 0 and
  // 2 every value of a turned frame must match the axes' frame.
  const Eigen::Vector3d receiverO(0, 0, 0), receiverU(1, 0, 0), receiverV(0, 1, 0);
  const Eigen::Vector3d sourceO(0, 1, 0), sourceU(1, 0, 0), sourceV(0, 0, 1);  // normal -y
  const std::vector<std::array<Eigen::Vector3d, 3>> occluders = {
      {Eigen::Vector3d(0.2, 0.7, 0.0), Eigen::Vector3d(0.4, 0, 0), Eigen::Vector3d(0, 0, 0.3)},
      {Eigen::Vector3d(0.2, 0.7, 0.3), Eigen::Vector3d(0.4, 0, 0), Eigen::Vector3d(0, 0.2, 0)},
      {Eigen::Vector3d(0.5, 1.0, 0.2), Eigen::Vector3d(0.4, 0, 0), Eigen::Vector3d(0, -0.2, 0)}};
  struct Values {
    double formFactor = 0.0;
    std::array<double, 9> quadratic{};
  };
  auto evaluate = [&](const RigidMotion& motion, const Eigen::Vector3d& point) {
    OccluderScene scene;
    for (const auto& o : occluders) scene.addParallelogram(motion.patch(o[0], o[1], o[2], "o"));
    scene.commit();
    const Patch receiver = motion.patch(receiverO, receiverU, receiverV, "receiver");
    const Patch source = motion.patch(sourceO, sourceU, sourceV, "source");
    const Link link{receiver, source, &scene};
    const Eigen::Vector3d x = motion.point(point);
    ExactVisibility visibility(link);
    VisibleRings rings;
    visibility.visibleRings(x, rings);
    Values values;
    values.formFactor = SourceMoments(source, 0).formFactor(x, receiver.normal, rings);
    SourceMoments(source, 2).compute(x, receiver.normal, rings, values.quadratic.data());
    return values;
  };
  std::mt19937_64 random(1);
  std::normal_distribution<double> normal;
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  double worst = 0.0;
  for (int trial = 0; trial < 600; ++trial) {
    const RigidMotion motion = randomMotion(random, normal, uniform);
    // Every third point close to the shared edge (y = 1), down to 1e-7 from it.
    const double u = uniform(random);
    const double v = trial % 3 == 0 ? 1.0 - std::pow(10.0, -1.0 - 6.0 * uniform(random))
                                    : uniform(random);
    const Eigen::Vector3d point(u, v, 0.0);
    const Values axes = evaluate(RigidMotion{}, point);
    const Values turned = evaluate(motion, point);
    ASSERT_TRUE(std::isfinite(turned.formFactor));
    double difference = std::fabs(axes.formFactor - turned.formFactor);
    for (int k = 0; k < 9; ++k) {
      ASSERT_TRUE(std::isfinite(turned.quadratic[std::size_t(k)]));
      difference = std::max(difference, std::fabs(axes.quadratic[std::size_t(k)] -
                                                  turned.quadratic[std::size_t(k)]));
    }
    EXPECT_LT(difference, 1e-8) << "trial " << trial << " at (" << u << ", " << v << ")";
    worst = std::max(worst, difference);
  }
  RecordProperty("worst_difference", std::to_string(worst));
}

TEST(ExactVisibility, AnOccluderLyingOnTheSourceHidesWhatItCoversInAnyFrame) {
  // A rectangle lying in the source's plane (either way up) and covering part of it hides
  // that part: what x sees is the source's form factor minus the covered rectangle's (closed
  // forms). In a turned and moved frame the rectangle's corners lie on the source's plane
  // only up to rounding; its shadow must still be the whole covered part, not a piece cut
  // along lines set by rounding.
  const HalfwaySetup setup;  // source at z = 1 over X, Y in [0, 1], facing down
  const double covered = setup.toSource() - setup.toRectangle(0.2, 0.6, 0.55, 1.0);
  std::mt19937_64 random(7);
  std::normal_distribution<double> normal;
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  double worst = 0.0;
  for (int trial = 0; trial < 400; ++trial) {
    const RigidMotion motion = trial > 0 ? randomMotion(random, normal, uniform) : RigidMotion{};
    // X in [0.2, 0.6], Y in [0.55, 1.3]: it reaches past the source's edge Y = 1.
    const bool up = trial % 2 == 0;
    const Patch rug = up ? motion.patch({0.2, 0.55, 1}, {0.4, 0, 0}, {0, 0.75, 0}, "rug")
                         : motion.patch({0.2, 1.3, 1}, {0.4, 0, 0}, {0, -0.75, 0}, "rug");
    OccluderScene scene;
    scene.addParallelogram(rug);
    scene.commit();
    const Patch receiver = motion.patch(setup.receiver, "receiver");
    const Patch source = motion.patch(setup.source, "source");
    const Link link{receiver, source, &scene};
    ExactVisibility visibility(link);
    VisibleRings rings;
    const Eigen::Vector3d x = motion.point(setup.x);
    visibility.visibleRings(x, rings);
    const double seen = SourceMoments(source, 0).formFactor(x, receiver.normal, rings);
    EXPECT_NEAR(seen, covered, 1e-10) << "trial " << trial << (up ? " (rug facing up)" : "");
    worst = std::max(worst, std::fabs(seen - covered));
  }
  EXPECT_LT(covered, 0.9 * setup.toSource());
  RecordProperty("worst_difference", std::to_string(worst));
}

}  // namespace
}  // namespace radquad
