// The exact visibility (reference/exact_visibility.h) against closed forms: shadows that
// overlap or not leave what inclusion and exclusion leave, and the three ways of subtracting
// their union (inclusion-exclusion, Clipper's union, the outline) agree on random scenes.
#include <gtest/gtest.h>

#include <Eigen/Core>

#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "kernel/occluder_scene.h"
#include "reference/exact_visibility.h"
#include "reference/point_polygon_form_factor.h"
#include "reference/source_moments.h"
#include "tests/reference/gold_agreement.h"
#include "tests/reference/halfway_occluders.h"

namespace radquad {
namespace {

TEST(ExactVisibility, OverlappingAndSeparateShadowsLeaveWhatInclusionExclusionLeaves) {
  // Three square occluders halfway: two shadows overlap (their union by inclusion-exclusion:
  // both, and their intersection added back), the third overlaps neither (counted as it is).
  OccluderScene scene;
  scene.addParallelogram(Patch::make({0.30, 0.30, 0.5}, {0.15, 0, 0}, {0, 0.15, 0}, "a"));
  scene.addParallelogram(Patch::make({0.40, 0.35, 0.5}, {0.10, 0, 0}, {0, 0.15, 0}, "b"));
  scene.addParallelogram(Patch::make({0.55, 0.55, 0.5}, {0.15, 0, 0}, {0, 0.15, 0}, "c"));
  scene.commit();
  const HalfwaySetup setup;
  const double expected = setup.toSource() - setup.toRectangle(0.1, 0.4, 0.1, 0.4) -
                          setup.toRectangle(0.3, 0.5, 0.2, 0.5) +
                          setup.toRectangle(0.3, 0.4, 0.2, 0.4) -
                          setup.toRectangle(0.6, 0.9, 0.6, 0.9);
  std::size_t unions = 0, rings = 0;
  EXPECT_NEAR(setup.visibleFormFactor(scene, unions, rings), expected, 1e-12);
  EXPECT_EQ(unions, 1u);
  EXPECT_EQ(rings, 5u);  // the source, the separate shadow, the other two, their intersection
  EXPECT_LT(expected, 0.9 * setup.toSource());
  // The outline: the source and the separate shadow as rings, the other two's outline as
  // pieces of their edges.
  EXPECT_NEAR(setup.visibleFormFactor(scene, unions, rings, ShadowUnion::outline), expected,
              1e-12);
  EXPECT_EQ(rings, 2u);
}

TEST(ExactVisibility, ThreeMutuallyOverlappingShadowsLeaveWhatInclusionExclusionLeaves) {
  // Shadows [0.1, 0.4]^2, [0.3, 0.6] x [0.2, 0.5] and [0.2, 0.5] x [0.3, 0.7]: every pair
  // overlaps and so do all three. The rectangles' form factors by the closed form, combined
  // by hand: the source's, minus the three, plus the three pairs' overlaps, minus the triple.
  OccluderScene scene;
  scene.addParallelogram(Patch::make({0.30, 0.30, 0.5}, {0.15, 0, 0}, {0, 0.15, 0}, "a"));
  scene.addParallelogram(Patch::make({0.40, 0.35, 0.5}, {0.15, 0, 0}, {0, 0.15, 0}, "b"));
  scene.addParallelogram(Patch::make({0.35, 0.40, 0.5}, {0.15, 0, 0}, {0, 0.20, 0}, "c"));
  scene.commit();
  const HalfwaySetup setup;
  const double expected =
      setup.toSource() - setup.toRectangle(0.1, 0.4, 0.1, 0.4) -
      setup.toRectangle(0.3, 0.6, 0.2, 0.5) - setup.toRectangle(0.2, 0.5, 0.3, 0.7) +
      setup.toRectangle(0.3, 0.4, 0.2, 0.4) + setup.toRectangle(0.2, 0.4, 0.3, 0.4) +
      setup.toRectangle(0.3, 0.5, 0.3, 0.5) - setup.toRectangle(0.3, 0.4, 0.3, 0.4);
  std::size_t unions = 0, rings = 0;
  EXPECT_NEAR(setup.visibleFormFactor(scene, unions, rings), expected, 1e-12);
  EXPECT_EQ(unions, 1u);
  EXPECT_EQ(rings, 8u);  // the source, three shadows, three pairs, the triple
  // Clipper's union instead: one ring for the three.
  EXPECT_NEAR(setup.visibleFormFactor(scene, unions, rings, ShadowUnion::clipper), expected,
              1e-12);
  EXPECT_EQ(rings, 2u);
  // The outline's pieces: the source alone as a ring.
  EXPECT_NEAR(setup.visibleFormFactor(scene, unions, rings, ShadowUnion::outline), expected,
              1e-12);
  EXPECT_EQ(rings, 1u);
}

TEST(ExactVisibility, InclusionExclusionAgreesWithClippersUnionOnRandomScenes) {
  // Random tilted quadrilaterals between the patches, 2 to 9 of them, seen from random
  // receiver points: the visible form factor with the overlapping shadows subtracted by
  // inclusion-exclusion, and with Clipper's union of them (a different algorithm, on an
  // integer grid of 2^-44), agree to 1e-12 of the source's, wherever shadows overlapped.
  const Patch receiver = Patch::make({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, "receiver");
  const Patch source = Patch::make({0.1, 1.1, 1}, {1, 0, 0.1}, {0.05, -1, 0}, "source");
  std::mt19937_64 random(17);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  int compared = 0;
  for (int scene = 0; scene < 40; ++scene) {
    OccluderScene occluders;
    const int count = 2 + scene % 8;
    for (int k = 0; k < count; ++k) {
      const Eigen::Vector3d corner(0.2 + 0.5 * uniform(random), 0.2 + 0.5 * uniform(random),
                                   0.3 + 0.4 * uniform(random));
      const Eigen::Vector3d u(0.1 + 0.2 * uniform(random), 0.1 * (uniform(random) - 0.5),
                              0.1 * (uniform(random) - 0.5));
      const Eigen::Vector3d v(0.1 * (uniform(random) - 0.5), 0.1 + 0.2 * uniform(random),
                              0.1 * (uniform(random) - 0.5));
      occluders.addParallelogram(Patch::make(corner, u, v, "quad"));
    }
    occluders.commit();
    const Link link{receiver, source, &occluders};
    ExactVisibility byParts(link, ShadowUnion::inclusionExclusion),
        byUnion(link, ShadowUnion::clipper);
    const SourceMoments moments(source, 0);
    VisibleRings parts, united;
    for (int point = 0; point < 10; ++point) {
      const Eigen::Vector3d x = receiver.pointAt(uniform(random), uniform(random));
      byParts.visibleRings(x, parts);
      byUnion.visibleRings(x, united);
      const double unoccluded = pointToPatchFormFactor(x, receiver.normal, source);
      EXPECT_NEAR(moments.formFactor(x, receiver.normal, parts),
                  moments.formFactor(x, receiver.normal, united), 1e-12 * unoccluded)
          << "scene " << scene << " point " << point;
    }
    compared += int(byParts.statistics().unions);
  }
  // The scenes overlap often enough for the comparison to mean something.
  EXPECT_GT(compared, 100);
}

TEST(ExactVisibility, TheOutlineAgreesWithClippersUnionOnRandomScenes) {
  // The union's outline as pieces of the shadows' edges against Clipper's union (rings on an
  // integer grid of 2^-44: a different algorithm), at degrees 0 and 2 (Lambert's formula and
  // the polar integral at 1e-14), on four kinds of random scene seen from random receiver
  // points: small tilted quadrilaterals; large ones, whose shadows the pyramid cuts along the
  // same lines (edges running the same way on one line); a quadrilateral cut in two along a
  // line, the halves touching (edges running opposite ways on one line), with a third
  // overlapping them; and tilted slats reaching past the source on both sides.
  const Patch receiver = Patch::make({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, "receiver");
  const Patch source = Patch::make({0.1, 1.1, 1}, {1, 0, 0.1}, {0.05, -1, 0}, "source");
  std::mt19937_64 random(23);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  const auto jitter = [&](double size) { return size * (uniform(random) - 0.5); };
  const auto quad = [&](double low, double spread, double side) {
    const Eigen::Vector3d corner(low + spread * uniform(random), low + spread * uniform(random),
                                 0.3 + 0.4 * uniform(random));
    const Eigen::Vector3d u(side * (0.5 + uniform(random)), jitter(0.1), jitter(0.1));
    const Eigen::Vector3d v(jitter(0.1), side * (0.5 + uniform(random)), jitter(0.1));
    return std::array<Eigen::Vector3d, 3>{corner, u, v};
  };
  const SourceMoments constant(source, 0), quadratic(source, 2);
  std::array<int, 4> unions{};
  double worst0 = 0.0, worst2 = 0.0;
  for (int scene = 0; scene < 80; ++scene) {
    const int kind = scene % 4;
    OccluderScene occluders;
    if (kind == 0 || kind == 1) {
      for (int k = 0, count = 2 + (scene / 4) % 6; k < count; ++k) {
        const auto [corner, u, v] = kind == 0 ? quad(0.2, 0.5, 0.2) : quad(-0.4, 0.9, 0.6);
        occluders.addParallelogram(Patch::make(corner, u, v, "quad"));
      }
    } else if (kind == 2) {
      const auto [corner, u, v] = quad(0.1, 0.5, 0.4);
      const double cut = 0.3 + 0.4 * uniform(random);
      occluders.addParallelogram(Patch::make(corner, cut * u, v, "left"));
      occluders.addParallelogram(Patch::make(corner + cut * u, (1.0 - cut) * u, v, "right"));
      const auto [corner2, u2, v2] = quad(0.2, 0.5, 0.3);
      occluders.addParallelogram(Patch::make(corner2, u2, v2, "third"));
    } else {
      const double tilt = jitter(0.6), step = 0.06 + 0.06 * uniform(random);
      for (int k = 0; k < 9; ++k) {
        const Eigen::Vector3d corner(-0.6, 0.1 + k * step, 0.4 + 0.02 * k);
        occluders.addParallelogram(
            Patch::make(corner, {2.2, 0, 0}, {0, 0.1, 0.1 * tilt}, "slat"));
      }
    }
    occluders.commit();
    const Link link{receiver, source, &occluders};
    ExactVisibility byOutline(link, ShadowUnion::outline), byClipper(link, ShadowUnion::clipper);
    VisibleRings outline, united;
    for (int point = 0; point < 12; ++point) {
      const Eigen::Vector3d x = receiver.pointAt(uniform(random), uniform(random));
      byOutline.visibleRings(x, outline);
      byClipper.visibleRings(x, united);
      expectPiecesCloseUp(outline, "scene " + std::to_string(scene) + " point " + std::to_string(point));
      const double unoccluded = pointToPatchFormFactor(x, receiver.normal, source);
      const double difference0 = std::fabs(constant.formFactor(x, receiver.normal, outline) -
                                            constant.formFactor(x, receiver.normal, united));
      EXPECT_LE(difference0, 1e-12 * unoccluded) << "scene " << scene << " point " << point;
      worst0 = std::max(worst0, difference0 / unoccluded);
      std::array<double, 9> a{}, b{};
      quadratic.compute(x, receiver.normal, outline, a.data());
      quadratic.compute(x, receiver.normal, united, b.data());
      for (int k = 0; k < 9; ++k) {
        const double difference = std::fabs(a[std::size_t(k)] - b[std::size_t(k)]);
        EXPECT_LE(difference, 1e-11 * unoccluded)
            << "scene " << scene << " point " << point << " moment " << k;
        worst2 = std::max(worst2, difference / unoccluded);
      }
    }
    unions[std::size_t(kind)] += int(byOutline.statistics().unions);
  }
  // Every kind of scene had points with overlapping shadows.
  for (int kind = 0; kind < 4; ++kind) EXPECT_GT(unions[std::size_t(kind)], 40) << "kind " << kind;
  RecordProperty("worst_difference_degree0", std::to_string(worst0));
  RecordProperty("worst_difference_degree2", std::to_string(worst2));
}

}  // namespace
}  // namespace radquad
