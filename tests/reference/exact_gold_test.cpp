// The exact-visibility gold: its pieces against independent computations, the whole against
// closed forms, the dense stratified gold, symmetry, and a much tighter run of itself.
#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <array>

#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "kernel/input_error.h"
#include "kernel/occluder_scene.h"
#include "kernel/patch_intersection.h"
#include "quadrature/gauss_legendre.h"
#include "reference/exact_gold.h"
#include "reference/exact_visibility.h"
#include "reference/gold_reference.h"
#include "reference/point_polygon_form_factor.h"
#include "reference/source_moments.h"
#include "tests/reference/gold_agreement.h"
#include "tests/support/analytic_form_factors.h"
#include "tests/support/polygon_form_factor.h"

namespace radquad {
namespace {

std::vector<Eigen::Vector3d> cornersOf(const Patch& patch) {
  const auto corners = patch.corners();
  return {corners.begin(), corners.end()};
}

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

// The dense stratified gold (an independent, random method) and the exact gold agree within
// 5 of the dense gold's standard errors on every coefficient. The standard error comes from
// R = 64 replicates, so a correct gold's deviation over it follows Student's t with 63 degrees
// of freedom: P(|t_63| > 5) = 4.9e-6 per coefficient, 5e-4 over the test's 98
// coefficients. (With R = 8 the estimated error itself is too uncertain: P(|t_7| > 4) = 0.005
// per coefficient.)
void expectAgreesWithDenseGold(const Link& link, int degree) {
  GoldOptions dense;
  dense.method = GoldMethod::stratified;
  dense.denseStrata = 16;
  dense.denseReplicates = 64;
  const GoldReference stratified = goldReference(link, degree, 11, dense);
  ASSERT_EQ(stratified.method, "dense stratified");
  const ExactGold exact = exactGold(link, degree);
  EXPECT_TRUE(exact.converged);
  const int n = int(exact.coupling.rows());
  for (int a = 0; a < n; ++a) {
    for (int b = 0; b < n; ++b) {
      EXPECT_LT(std::fabs(exact.coupling(a, b) - stratified.coupling(a, b)),
                5.0 * stratified.couplingError(a, b) + 1e-12)
          << "K[" << a << "][" << b << "] degree " << degree;
    }
  }
}

// J_m(R, H) = int_0^R rho^m / (rho^2 + H^2)^2 by 20-point Gauss on `pieces` pieces graded
// towards 0 (where the integrand varies on the scale H) as (p / pieces)^grading, in long double.
long double gradedRadialMoment(double R, double H, int m, int pieces, double grading) {
  const GaussLegendreRule& rule = gaussLegendreUnit(20);
  long double sum = 0.0L;
  for (int p = 0; p < pieces; ++p) {
    const double a = R * std::pow(double(p) / pieces, grading);
    const double b = R * std::pow(double(p + 1) / pieces, grading);
    for (int k = 0; k < 20; ++k) {
      const long double rho = a + (b - a) * rule.nodes[k];
      const long double d = rho * rho + (long double)H * H;
      sum += (b - a) * rule.weights[k] * std::pow(rho, m) / (d * d);
    }
  }
  return sum;
}

TEST(RadialMoments, MatchCompositeGaussIntegrationAtEveryScale) {
  // Against 200 pieces of 20-point Gauss.
  for (const double H : {1e-3, 0.3, 1.0, 7.0}) {
    for (const double R : {1e-3, 0.05, 0.9, 2.5, 40.0}) {
      double J[19];
      radialMoments(R, H, 18, J);
      for (int m = 0; m <= 18; ++m) {
        const long double expected = gradedRadialMoment(R, H, m, 200, 3.0);
        EXPECT_NEAR(J[m], double(expected), 1e-12 * std::fabs(double(expected)))
            << "m " << m << " R " << R << " H " << H;
      }
    }
  }
}

TEST(RadialMoments, LowPowersMatchCompositeGaussIntegrationAcrossEveryRule) {
  // Powers up to 8 (degree <= 3) take 8 or 12 Gauss points or the recurrences by R / H:
  // every branch and both sides of each switch (0.15, 0.85), against 400 pieces of
  // 20-point Gauss in long double, graded towards 0.
  for (const int maxPower : {4, 6, 8}) {
    for (const double X : {1e-4, 0.01, 0.1, 0.15, 0.1501, 0.3, 0.45, 0.4501, 0.6, 0.85, 0.8501,
                           0.87, 1.0, 1.3, 1.9, 2.0, 2.01, 3.0, 30.0}) {
      const double H = 0.7, R = X * H;
      double J[9];
      radialMoments(R, H, maxPower, J);
      for (int m = 0; m <= maxPower; ++m) {
        const long double expected = gradedRadialMoment(R, H, m, 400, 2.0);
        EXPECT_NEAR(J[m], double(expected), 5e-14 * std::fabs(double(expected)))
            << "m " << m << " of " << maxPower << ", R / H " << X;
      }
    }
  }
}

// Every lane of laneRadialMoments (the loose form or not) on each batch, at the powers 2, 4, 6
// and 8, against 400 pieces of 20-point Gauss in long double, within bound(maxPower) relative.
template <class Bound>
void expectLanesMatchQuadrature(const std::vector<std::array<double, 8>>& batches, bool loose,
                                const Bound& bound) {
  for (const int maxPower : {2, 4, 6, 8}) {
    for (const auto& X : batches) {
      double out[9 * 8];
      laneRadialMoments(X.data(), maxPower, out, loose);
      for (int k = 0; k < 8; ++k) {
        for (int m = 0; m <= maxPower; ++m) {
          const long double expected = gradedRadialMoment(X[std::size_t(k)], 1.0, m, 400, 2.0);
          EXPECT_NEAR(out[m * 8 + k], double(expected),
                      bound(maxPower) * std::fabs(double(expected)))
              << "m " << m << " of " << maxPower << ", X " << X[std::size_t(k)];
        }
      }
    }
  }
}

TEST(RadialMoments, EightLanesMatchCompositeGaussIntegrationWhateverTheirNeighbours) {
  // The inner integral's eight-lane form (degrees 0-3): the 12-point rule up to 0.85, the
  // recurrences (glibc's vector atan and log1p where built with them) above. Batches all on
  // one side of the switch, and batches that straddle it (each lane must keep its own
  // branch), against 400 pieces of 20-point Gauss in long double. The bound allows glibc's
  // documented 4 units in the last place of the vector atan and log1p, which the recurrences
  // amplify about 3.5 times at the switch (j_8 at R / H = 0.85 is 0.01): 2e-13 relative.
  const std::vector<std::array<double, 8>> batches = {
      {1e-4, 0.01, 0.1, 0.15, 0.3, 0.5, 0.7, 0.85},
      {0.8501, 0.87, 1.0, 1.3, 2.0, 3.0, 30.0, 300.0},
      {0.84, 0.86, 1e-3, 5.0, 0.85, 0.8500001, 0.31, 0.35},
  };
  expectLanesMatchQuadrature(batches, false, [](int) { return 2e-13; });
  double out[9 * 8];
  const double X[8] = {1, 1, 1, 1, 1, 1, 1, 1};
  EXPECT_THROW(laneRadialMoments(X, 5, out), InputError);
}

TEST(RadialMoments, LooseLanesStayWithinTheirBoundWhateverTheirNeighbours) {
  // The loose eight-lane form (accuracy 1e-6 or more): the 8-point rule up to 0.15, the
  // recurrences above, which lose digits as R / H falls. Against the same long-double
  // quadrature: 3e-10 relative up to the power 6 and 3e-8 at the power 8 (just above 0.15
  // the recurrences err by 1.3e-10 and 1.2e-8 with glibc's vector atan and log1p, 5e-11 and
  // 5e-9 with the scalar ones), on batches below, above and straddling the switch.
  const std::vector<std::array<double, 8>> batches = {
      {1e-4, 0.01, 0.05, 0.1, 0.12, 0.149, 0.15, 0.15},
      {0.1500001, 0.16, 0.2, 0.3, 0.5, 0.85, 3.0, 300.0},
      {0.14, 0.16, 1e-3, 5.0, 0.15, 0.1500001, 0.31, 0.85},
  };
  expectLanesMatchQuadrature(batches, true,
                             [](int maxPower) { return maxPower == 8 ? 3e-8 : 3e-10; });
}

TEST(SourceMoments, LooseAccuracyStaysWithinItsBoundOfTheAccurateIntegrals) {
  // The 8-point edge rule (accuracy 1e-6: error at most 2e-7 of the largest moment) against
  // the 12-point one (about 1e-14), at degrees 1 and 2, from points near (a twentieth of the
  // source's size) and far, above the interior and beyond the edges, on rings with a hole.
  // Degree 3 keeps the 12 points at any accuracy: the same values.
  const Patch source = Patch::make({0, 1, 1}, {1, 0, 0.2}, {0.1, -1, 0}, "source");
  VisibleRings rings;
  rings.add({{0, 0}, {1, 0}, {1, 1}, {0, 1}}, 1.0);
  rings.add({{0.2, 0.3}, {0.7, 0.25}, {0.5, 0.8}}, -1.0);
  std::mt19937_64 random(5);
  std::uniform_real_distribution<double> uniform(-0.5, 1.5);
  const Eigen::Vector3d normal = Eigen::Vector3d(0.1, -0.2, 1).normalized();
  for (const int degree : {1, 2, 3}) {
    const SourceMoments accurate(source, degree, 1e-14), loose(source, degree, 1e-6);
    const bool same = degree == 3;
    const int n = accurate.functions();
    std::vector<double> a(static_cast<std::size_t>(n)), b(static_cast<std::size_t>(n));
    int compared = 0;
    for (int k = 0; k < 60; ++k) {
      const Eigen::Vector3d x(uniform(random), uniform(random),
                              0.002 + 0.6 * (uniform(random) + 0.5));
      // The whole source in front of x's tangent plane (the visible part is clipped so).
      bool front = source.normal.dot(x - source.origin) > 0.0;
      for (const Eigen::Vector3d& corner : source.corners()) front = front && normal.dot(corner - x) > 0.0;
      if (!front) continue;
      accurate.compute(x, normal, rings, a.data());
      loose.compute(x, normal, rings, b.data());
      double largest = 0.0, difference = 0.0;
      for (int j = 0; j < n; ++j) {
        largest = std::max(largest, std::fabs(a[std::size_t(j)]));
        difference = std::max(difference, std::fabs(a[std::size_t(j)] - b[std::size_t(j)]));
      }
      EXPECT_LE(difference, same ? 0.0 : 2e-7 * largest) << "degree " << degree << " point " << k;
      // The looser rules differ: the test compares two computations, not one twice.
      if (difference > 0.0) ++compared;
    }
    if (!same) {
      EXPECT_GT(compared, 0) << "degree " << degree;
    }
  }
}

TEST(SourceMoments, PolarMethodReproducesLambertsFormula) {
  // Degree 0 both ways (contour formula, polar integration), on the source and on rings with
  // a hole, from points near and far, above the interior and beyond the edges.
  const Patch source = Patch::make({0, 1, 1}, {1, 0, 0.2}, {0.1, -1, 0}, "source");
  const SourceMoments moments(source, 0);
  VisibleRings rings;
  rings.add({{0, 0}, {1, 0}, {1, 1}, {0, 1}}, 1.0);
  rings.add({{0.2, 0.3}, {0.7, 0.25}, {0.5, 0.8}}, -1.0);
  std::mt19937_64 random(3);
  std::uniform_real_distribution<double> uniform(-0.5, 1.5);
  const Eigen::Vector3d normal(0, 0, 1);
  for (int k = 0; k < 40; ++k) {
    const Eigen::Vector3d x(uniform(random), uniform(random), 0.001 + 0.3 * (uniform(random) + 0.5));
    if (source.normal.dot(x - source.origin) <= 0.0) continue;
    double polar = 0.0;
    moments.computePolar(x, normal, rings, &polar);
    const double lambert = moments.formFactor(x, normal, rings);
    EXPECT_NEAR(polar, lambert, 1e-12 * std::fabs(lambert) + 1e-15) << "point " << k;
  }
}

// The unit receiver at z = 0 seen from its centre x, and the unit source facing it at z = 1.
// Occluders halfway between them and parallel to both cast shadows that are the occluders
// scaled by 2 about x's foot, so the visible form factor follows from closed-form
// point-to-rectangle form factors by inclusion and exclusion: no ring, no union, no clipping.
struct HalfwaySetup {
  const Patch receiver = Patch::make({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, "receiver");
  const Patch source = Patch::make({0, 1, 1}, {1, 0, 0}, {0, -1, 0}, "source");
  const Eigen::Vector3d x{0.5, 0.5, 0.0}, n{0, 0, 1};

  // The form factor from x to the rectangle [x0, x1] x [y0, y1] of the source's plane,
  // facing the receiver as the source does.
  double toRectangle(double x0, double x1, double y0, double y1) const {
    return pointToPatchFormFactor(
        x, n, Patch::make({x0, y1, 1}, {x1 - x0, 0, 0}, {0, y0 - y1, 0}, "shadow"));
  }
  double toSource() const { return pointToPatchFormFactor(x, n, source); }

  // What x sees of the source past `scene`'s occluders, by the exact visibility and
  // Lambert's formula; `unions` and `rings` report how it was formed.
  double visibleFormFactor(const OccluderScene& scene, std::size_t& unions, std::size_t& rings,
                           ShadowUnion method = ShadowUnion::inclusionExclusion) const {
    const Link link{receiver, source, &scene};
    ExactVisibility visibility(link, method);
    VisibleRings visible;
    visibility.visibleRings(x, visible);
    unions = visibility.statistics().unions;
    rings = visible.count();
    return SourceMoments(source, 0).formFactor(x, n, visible);
  }
};

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

TEST(ExactGold, AgreesWithTheDenseStratifiedGoldOnOccludedLinks) {
  const Patch receiver = Patch::make({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, "receiver");
  const Patch source = Patch::make({0, 1, 1}, {1, 0, 0}, {0, -1, 0}, "source");
  {  // two overlapping tilted blockers: their shadows need a polygon union
    OccluderScene scene;
    addTwoTiltedBlockers(scene);
    scene.commit();
    const Link link{receiver, source, &scene};
    expectAgreesWithDenseGold(link, 0);
    expectAgreesWithDenseGold(link, 2);
  }
  {  // an occluder crossing the receiver's plane, and one touching the source
    OccluderScene scene;
    scene.addParallelogram(Patch::make({0.4, -0.3, -0.3}, {0, 0.9, 0}, {0.1, 0, 0.7}, "crossing"));
    scene.addParallelogram(Patch::make({0.6, 0.2, 1.0}, {0, 0.5, 0}, {0, 0, -0.4}, "touching"));
    scene.commit();
    expectAgreesWithDenseGold(Link{receiver, source, &scene}, 1);
  }
}

TEST(ExactGold, ATriangleSoupIsCulledToItsShaftAndAgreesWithTheDenseGold) {
  // 1,000 small triangles, most of them away from the link: the shaft cull keeps few.
  std::mt19937_64 random(8);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  std::vector<Eigen::Vector3d> vertices;
  std::vector<std::array<std::uint32_t, 3>> triangles;
  for (std::uint32_t t = 0; t < 1000; ++t) {
    const Eigen::Vector3d centre(6 * uniform(random) - 2.5, 6 * uniform(random) - 2.5,
                                 0.2 + 0.6 * uniform(random));
    for (int c = 0; c < 3; ++c) {
      vertices.push_back(centre + 0.08 * Eigen::Vector3d(uniform(random) - 0.5,
                                                         uniform(random) - 0.5,
                                                         uniform(random) - 0.5));
    }
    triangles.push_back({3 * t, 3 * t + 1, 3 * t + 2});
  }
  OccluderScene scene;
  scene.addTriangleMesh(vertices, triangles);
  scene.commit();
  const Patch receiver = Patch::make({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, "receiver");
  const Patch source = Patch::make({0, 1, 1}, {1, 0, 0}, {0, -1, 0}, "source");
  const Link link{receiver, source, &scene};
  const ExactVisibility visibility(link);
  EXPECT_LT(visibility.candidateCount(), 100u);
  EXPECT_GT(visibility.candidateCount(), 5u);
  expectAgreesWithDenseGold(link, 0);
}

TEST(ExactGold, TheErrorEstimateBoundsTheTrueError) {
  // Over varied occluded links, the error reported at a loose tolerance exceeds the
  // difference from a run 1,000 times tighter, for every coefficient.
  std::mt19937_64 random(21);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  const Patch receiver = Patch::make({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, "receiver");
  int checked = 0;
  for (int k = 0; k < 12; ++k) {
    const double height = 0.5 + 1.5 * uniform(random);
    const Patch source = Patch::make({uniform(random) - 0.5, 1.0 + uniform(random), height},
                                     {1.0, 0.0, 0.3 * uniform(random)},
                                     {0.2 * uniform(random), -1.0, 0.0}, "source");
    OccluderScene scene;
    for (int b = 0; b < 1 + k % 3; ++b) {
      scene.addParallelogram(Patch::make(
          {uniform(random) - 0.3, uniform(random) - 0.3, height * (0.2 + 0.6 * uniform(random))},
          {0.2 + 0.4 * uniform(random), 0.1 * uniform(random), 0.1 * uniform(random)},
          {0.1 * uniform(random), 0.2 + 0.4 * uniform(random), 0.0}, "blocker"));
    }
    scene.commit();
    const Link link{receiver, source, &scene};
    const int degree = k % 2;
    ExactGoldOptions loose, tight;
    loose.tolerance = 1e-4;
    tight.tolerance = 1e-7;
    const ExactGold estimate = exactGold(link, degree, loose);
    const ExactGold truth = exactGold(link, degree, tight);
    if (truth.coupling(0, 0) <= 0.0) continue;
    ++checked;
    const Eigen::MatrixXd error = (estimate.coupling - truth.coupling).cwiseAbs();
    for (int a = 0; a < error.rows(); ++a) {
      for (int b = 0; b < error.cols(); ++b) {
        EXPECT_LE(error(a, b), estimate.couplingError(a, b) + truth.couplingError(a, b))
            << "link " << k << " K[" << a << "][" << b << "]";
      }
    }
  }
  EXPECT_GE(checked, 10);
}

// Two integrations of one K, with different integrands on the receiver: S' minus the
// shadows at every point, or S' apart (Gauss products of rising order) and the shadows
// alone (the default at degree >= 1). Each must fall within the other's error.
void expectApartAgreesWithTogether(const Link& link, int degree, double tolerance) {
  ExactGoldOptions apart, together;
  apart.tolerance = together.tolerance = tolerance;
  together.unoccludedApart = false;
  const ExactGold a = exactGold(link, degree, apart), b = exactGold(link, degree, together);
  EXPECT_TRUE(a.unoccludedApart);
  EXPECT_FALSE(b.unoccludedApart);
  EXPECT_TRUE(a.converged);
  EXPECT_TRUE(b.converged);
  const double largest = b.coupling.cwiseAbs().maxCoeff();
  EXPECT_LE(a.couplingError.maxCoeff(), tolerance * largest * (1 + 1e-9));
  expectWithinSummedErrors(a, b, "degree " + std::to_string(degree));
}

TEST(ExactGold, TheUnoccludedPartApartAgreesWithTheWholeIntegral) {
  const Patch receiver = Patch::make({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, "receiver");
  const Patch source = Patch::make({0, 1, 1}, {1, 0, 0}, {0, -1, 0}, "source");
  {  // two overlapping tilted blockers
    OccluderScene scene;
    addTwoTiltedBlockers(scene);
    scene.commit();
    for (const int degree : {1, 2}) expectApartAgreesWithTogether({receiver, source, &scene}, degree, 1e-6);
  }
  {  // a blocker hiding all but a sliver (x_r + x_s > 1.99): K's largest entry is about 1e-4
     // of its unoccluded part's, whose error must then be held far below its own tolerance
     // (higher Gauss orders after the shadows' part)
    OccluderScene scene;
    scene.addParallelogram(Patch::make({-0.5, -0.5, 0.5}, {1.499, 0, 0}, {0, 2.0, 0}, "blocker"));
    scene.commit();
    const Link link{receiver, source, &scene};
    expectApartAgreesWithTogether(link, 2, 1e-5);
    const ExactGold gold = exactGold(link, 0);
    EXPECT_LT(gold.formFactor, 0.1 * analytic::parallelRectangles(1, 1, 1));
    EXPECT_FALSE(gold.unoccludedApart);  // degree 0: Lambert's formula costs S' four edges
  }
  {  // a receiver crossing the source's plane: S' is not the same from every point
    OccluderScene scene;
    scene.addParallelogram(Patch::make({0.2, 0.2, 0.5}, {0.4, 0, 0}, {0, 0.4, 0}, "blocker"));
    scene.commit();
    const Patch tilted = Patch::make({0, 0, 0}, {1, 0, 0}, {0, 0.5, 1.5}, "tilted");
    ExactGoldOptions options;
    options.tolerance = 1e-5;
    const ExactGold gold = exactGold({tilted, source, &scene}, 1, options);
    EXPECT_FALSE(gold.unoccludedApart);
    EXPECT_TRUE(gold.converged);
  }
}

TEST(ExactGold, AGrazingLinkKeepsItsErrorEstimate) {
  // A receiver beside the source and a twentieth of its size above its plane sees it at
  // grazing angles: its points' inner integrals are small sums of large terms that cancel.
  // At the study's tolerance the gold, with its unoccluded part apart or not, must stay within
  // its estimate of a run at 1e-8 (tight inner rules, the whole integral at once). With the
  // loose inner rules in the unoccluded part its actual error reached 6, 100 and 174 times
  // its estimate (degrees 1-3), and 3 times at degree 3 with the loose rules everywhere.
  const Patch source = Patch::make({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, "source");
  const Patch receiver = Patch::make({1.3, 1, 0.05}, {0, -1, 0}, {1, 0, 0.05}, "receiver");
  OccluderScene scene;
  scene.addParallelogram(Patch::make({1.1, 0.2, 0.0005}, {0, 0.3, 0}, {0, 0, 0.01}, "blocker"));
  scene.commit();
  const Link link{receiver, source, &scene};
  for (const int degree : {1, 2, 3}) {
    ExactGoldOptions tight;
    tight.tolerance = 1e-8;
    tight.unoccludedApart = false;
    const ExactGold truth = exactGold(link, degree, tight);
    ASSERT_TRUE(truth.converged);
    for (const bool apart : {true, false}) {
      ExactGoldOptions study;
      study.tolerance = 3e-4;
      study.unoccludedApart = apart;
      const ExactGold gold = exactGold(link, degree, study);
      EXPECT_EQ(gold.unoccludedApart, apart);
      EXPECT_TRUE(gold.converged);
      expectWithinSummedErrors(gold, truth, "degree " + std::to_string(degree) + " apart " +
                                                std::to_string(apart));
    }
  }
}

TEST(ExactGold, IsDeterministic) {
  OccluderScene scene;
  scene.addParallelogram(Patch::make({0.1, 0.1, 0.4}, {0.5, 0.1, 0.05}, {0.05, 0.5, 0}, "a"));
  scene.commit();
  const Link link{Patch::make({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, "receiver"),
                  Patch::make({0, 1, 1}, {1, 0, 0}, {0, -1, 0}, "source"), &scene};
  const ExactGold first = exactGold(link, 1), second = exactGold(link, 1);
  EXPECT_EQ(first.coupling, second.coupling);
  EXPECT_EQ(first.couplingError, second.couplingError);
}

}  // namespace
}  // namespace radquad
