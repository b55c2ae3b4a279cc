// The critical-line outer integration of the exact gold: its Gauss-Kronrod pair against
// exactness degrees, its segments against events placed by hand, and the whole against the
// Genz-Malik cubature of the same integrand (a second outer method).
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "kernel/occluder_scene.h"
#include "reference/critical_segments.h"
#include "reference/exact_gold.h"
#include "reference/gauss_kronrod.h"
#include "tests/reference/gold_agreement.h"

namespace radquad {
namespace {

double kronrodMoment(const GaussKronrodPair& pair, int power, bool gauss) {
  double sum = 0.0;
  for (int j = 0; j < pair.points(); ++j) {
    sum += (gauss ? pair.gaussWeight(j) : pair.kronrodWeight(j)) * std::pow(pair.node(j), power);
  }
  return sum;
}

// The n-point Gauss rule is exact to degree 2n - 1 and its 2n + 1-point Kronrod extension to
// 3n + 2 (n odd), and neither beyond.
TEST(GaussKronrod, ThePairsAreExactToTheirDegreesAndNoFurther) {
  for (const GaussKronrodPair* pair :
       {&GaussKronrodPair::sevenPoint(), &GaussKronrodPair::fifteenPoint()}) {
    const int n = pair->gaussPoints();
    ASSERT_EQ(pair->points(), 2 * n + 1);
    const int kronrodDegree = 3 * n + 2, gaussDegree = 2 * n - 1;
    for (int power = 0; power <= kronrodDegree; ++power) {
      const double exact = power % 2 == 1 ? 0.0 : 2.0 / double(power + 1);
      EXPECT_NEAR(kronrodMoment(*pair, power, false), exact, 1e-15) << n << " " << power;
      if (power <= gaussDegree) {
        EXPECT_NEAR(kronrodMoment(*pair, power, true), exact, 1e-15) << n << " " << power;
      }
    }
    EXPECT_GT(std::fabs(kronrodMoment(*pair, kronrodDegree + 1, false) - 2.0 / (kronrodDegree + 2)), 1e-12);
    EXPECT_GT(std::fabs(kronrodMoment(*pair, gaussDegree + 1, true) - 2.0 / (gaussDegree + 2)), 1e-6);
    int gaussNodes = 0;
    for (int j = 0; j < pair->points(); ++j) {
      gaussNodes += pair->gaussWeight(j) > 0.0;
      if (j > 0) {
        EXPECT_LT(pair->node(j - 1), pair->node(j));
      }
    }
    EXPECT_EQ(gaussNodes, n);
  }
}

// Unit squares 1 apart, a blocker [0.25, 0.75]^2 halfway: by similar triangles every event
// (a blocker corner seen on a source edge, a source corner seen on a blocker edge) happens
// where the receiver's s or t is 2 c - e with c in {0.25, 0.75}, e in {0, 1}: on s = 0.5 or
// t = 0.5 only, and along the whole of both.
TEST(CriticalSegments, ACentredBlockerHalfwayGivesTheTwoMidLines) {
  const Patch receiver = Patch::make({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, "receiver");
  const Patch source = Patch::make({0, 1, 1}, {1, 0, 0}, {0, -1, 0}, "source");
  const std::vector<std::vector<Eigen::Vector3d>> blocker = {
      {{0.25, 0.25, 0.5}, {0.75, 0.25, 0.5}, {0.75, 0.75, 0.5}, {0.25, 0.75, 0.5}}};
  const std::vector<ReceiverSegment> segments = criticalSegments(receiver, source, blocker);
  ASSERT_FALSE(segments.empty());
  for (const auto& segment : segments) {
    const bool alongT = std::fabs(segment.a.x() - 0.5) < 1e-12 && std::fabs(segment.b.x() - 0.5) < 1e-12;
    const bool alongS = std::fabs(segment.a.y() - 0.5) < 1e-12 && std::fabs(segment.b.y() - 0.5) < 1e-12;
    EXPECT_TRUE(alongS || alongT) << segment.a.transpose() << " - " << segment.b.transpose();
  }
  for (int k = 1; k < 100; ++k) {
    const double u = 0.01 * k;
    bool onS = false, onT = false;
    for (const auto& segment : segments) {
      const double sLow = std::min(segment.a.x(), segment.b.x()), sHigh = std::max(segment.a.x(), segment.b.x());
      const double tLow = std::min(segment.a.y(), segment.b.y()), tHigh = std::max(segment.a.y(), segment.b.y());
      onS = onS || (std::fabs(segment.a.y() - 0.5) < 1e-12 && sLow <= u && u <= sHigh);
      onT = onT || (std::fabs(segment.a.x() - 0.5) < 1e-12 && tLow <= u && u <= tHigh);
    }
    EXPECT_TRUE(onS && onT) << u;
  }
}

// A source crossing the receiver's plane: the line where the two planes meet bounds the
// receiver points in front of the source (the clamped cosine at the source).
TEST(CriticalSegments, TheSourcePlaneCrossingTheReceiverIsALine) {
  const Patch receiver = Patch::make({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, "receiver");
  // The plane x = 0.3 + 0.5 z, facing -x, crossing the receiver along s = 0.3.
  const Patch source = Patch::make({0.3, 0, 0}, {0, 1, 0}, {0.5, 0, 1}, "source");
  const std::vector<ReceiverSegment> segments = criticalSegments(receiver, source, {});
  ASSERT_EQ(segments.size(), 1u);
  EXPECT_NEAR(segments[0].a.x(), 0.3, 1e-12);
  EXPECT_NEAR(segments[0].b.x(), 0.3, 1e-12);
  EXPECT_NEAR(std::fabs(segments[0].b.y() - segments[0].a.y()), 1.0, 1e-12);
}

// A vertical plate at x = 0.5 between opposed squares: from a receiver point at distance d
// from the plate's plane, the blocked width of the source grows as |d| (a kink at d = 0),
// and no vertex-edge pair of two different polygons lies on s = 0.5: the plate's own plane
// gives that line.
TEST(CriticalSegments, AnOccluderSeenEdgeOnGivesTheLineOfItsPlane) {
  const Patch receiver = Patch::make({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, "receiver");
  const Patch source = Patch::make({0, 1, 1}, {1, 0, 0}, {0, -1, 0}, "source");
  const std::vector<std::vector<Eigen::Vector3d>> plate = {
      {{0.5, -1, 0.3}, {0.5, 2, 0.3}, {0.5, 2, 0.7}, {0.5, -1, 0.7}}};
  bool found = false;
  for (const auto& segment : criticalSegments(receiver, source, plate)) {
    found = found || (std::fabs(segment.a.x() - 0.5) < 1e-12 &&
                      std::fabs(segment.b.x() - 0.5) < 1e-12 &&
                      std::fabs(std::fabs(segment.b.y() - segment.a.y()) - 1.0) < 1e-12);
  }
  EXPECT_TRUE(found);
}

// The same integrand, two outer methods: critical lines (exponential convergence between
// breakpoints) and Genz-Malik (bisection blind to them) agree within their summed estimates.
void expectOuterMethodsAgree(const Link& link, int degree) {
  ExactGoldOptions lines;
  lines.tolerance = 1e-9;
  lines.maxFloorPoints = lines.maxFloorPointsHigherDegrees = 1000000;  // always critical lines
  ExactGoldOptions genz;
  genz.outer = ExactOuterMethod::genzMalik;
  genz.tolerance = 1e-6;
  const ExactGold a = exactGold(link, degree, lines);
  const ExactGold b = exactGold(link, degree, genz);
  ASSERT_EQ(a.outer, ExactOuterMethod::criticalLines);
  ASSERT_EQ(b.outer, ExactOuterMethod::genzMalik);
  EXPECT_TRUE(a.converged);
  EXPECT_TRUE(b.converged);
  EXPECT_GT(a.criticalSegments, 0u);
  expectWithinSummedErrors(a, b, "degree " + std::to_string(degree), 1e-15);
}

TEST(CriticalSegments, AnOccluderMeetingTheReceiverGivesItsContactSegment) {
  const Patch receiver = Patch::make({0, 0, 0}, {2, 0, 0}, {0, 1, 0}, "receiver");
  auto contacts = [&](const Patch& occluder) {
    const auto corners = occluder.corners();
    return contactSegments(receiver, {{corners.begin(), corners.end()}});
  };
  // A wall standing on the receiver along x = 1, longer than it: s = 0.5, t from 0 to 1.
  const auto standing = contacts(Patch::make({1, -0.5, 0}, {0, 2, 0}, {0, 0, 1}, "wall"));
  ASSERT_EQ(standing.size(), 1u);
  EXPECT_NEAR(standing[0].a.x(), 0.5, 1e-15);
  EXPECT_NEAR(standing[0].b.x(), 0.5, 1e-15);
  EXPECT_NEAR(std::fabs(standing[0].b.y() - standing[0].a.y()), 1.0, 1e-15);
  // A tilted panel passing through it, crossing the plane along y = 0.05 + 0.4 * 0.2 / 0.8 = 0.15
  // for x in [0.4, 1.2].
  const auto crossing = contacts(Patch::make({0.4, 0.05, -0.2}, {0.8, 0, 0}, {0, 0.4, 0.8}, "panel"));
  ASSERT_EQ(crossing.size(), 1u);
  EXPECT_NEAR(std::fabs(crossing[0].b.x() - crossing[0].a.x()), 0.4, 1e-15);
  EXPECT_NEAR(crossing[0].a.y(), 0.15, 1e-15);
  EXPECT_NEAR(crossing[0].b.y(), 0.15, 1e-15);
  // None: lifted off the receiver, standing outside it, lying in its plane, or behind it.
  EXPECT_TRUE(contacts(Patch::make({1, 0.2, 0.01}, {0, 0.5, 0}, {0, 0, 1}, "lifted")).empty());
  EXPECT_TRUE(contacts(Patch::make({3, 0.2, 0}, {0, 0.5, 0}, {0, 0, 1}, "outside")).empty());
  EXPECT_TRUE(contacts(Patch::make({0.5, 0.2, 0}, {0.5, 0, 0}, {0, 0.5, 0}, "rug")).empty());
  EXPECT_TRUE(contacts(Patch::make({1, 0.2, 0}, {0, 0.5, 0}, {0, 0, -1}, "below")).empty());
}

TEST(CriticalLines, AgreeWithGenzMalikOnOccludedLinks) {
  const Patch receiver = Patch::make({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, "receiver");
  const Patch source = Patch::make({0, 1, 1}, {1, 0, 0}, {0, -1, 0}, "source");
  {  // two overlapping tilted blockers
    OccluderScene scene;
    addTwoTiltedBlockers(scene);
    scene.commit();
    expectOuterMethodsAgree(Link{receiver, source, &scene}, 0);
    expectOuterMethodsAgree(Link{receiver, source, &scene}, 2);
  }
  {  // a tilted plate seen edge-on from a line across the receiver
    OccluderScene scene;
    scene.addParallelogram(Patch::make({0.45, -0.5, 0.3}, {0, 2, 0}, {0.1, 0, 0.4}, "plate"));
    scene.commit();
    expectOuterMethodsAgree(Link{receiver, source, &scene}, 0);
  }
  {  // a steep source whose plane crosses the receiver, a blocker crossing the receiver's plane
    const Patch steep = Patch::make({1.0, 0.1, 0.9}, {0, 0.8, 0}, {-0.2, 0, -0.8}, "steep");
    OccluderScene scene;
    scene.addParallelogram(Patch::make({0.5, -0.3, -0.3}, {0, 0.9, 0}, {0.1, 0, 0.7}, "crossing"));
    scene.commit();
    expectOuterMethodsAgree(Link{receiver, steep, &scene}, 1);
  }
}

// Many segments: the breakpoints' grid would cost more than bisection; Genz-Malik is used.
TEST(CriticalLines, ManySegmentsFallBackToGenzMalik) {
  const Patch receiver = Patch::make({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, "receiver");
  const Patch source = Patch::make({0, 1, 1}, {1, 0, 0}, {0, -1, 0}, "source");
  OccluderScene scene;
  for (int k = 0; k < 12; ++k) {  // a grid of small tilted tiles
    const double x = 0.05 + 0.3 * (k % 4), y = 0.1 + 0.3 * (k / 4);
    scene.addParallelogram(Patch::make({x, y, 0.3 + 0.03 * k}, {0.15, 0.02, 0.01}, {0.01, 0.15, 0.02}, "tile"));
  }
  scene.commit();
  ExactGoldOptions options;
  options.tolerance = 1e-5;
  const ExactGold gold = exactGold(Link{receiver, source, &scene}, 0, options);
  EXPECT_GT(gold.criticalSegments, 100u);
  EXPECT_EQ(gold.outer, ExactOuterMethod::genzMalik);
  EXPECT_TRUE(gold.converged);
}

}  // namespace
}  // namespace radquad
