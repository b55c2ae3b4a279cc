// The shadows' union on the study's own links: the outline (the exact gold's default) against
// Clipper's union, a different algorithm, at the receiver points of the partial links the
// study's generator draws (one blocker, several blockers, slats).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "experiments/scenarios/probed_links.h"
#include "reference/exact_visibility.h"
#include "reference/point_polygon_form_factor.h"
#include "reference/source_moments.h"
#include "tests/reference/gold_agreement.h"

namespace radquad {
namespace {

TEST(ShadowUnion, TheOutlineAgreesWithClippersUnionOnTheStudysLinks) {
  // 8 links of each kind from seed 5. At degree 0 (Lambert's formula) on a grid of 100 x 100
  // receiver points (a dense grid: a wrong outline shows at a few points in 10,000, along the
  // lines where a shadow's edge meets S''s border), and at degree 2 (the polar integral at
  // 1e-14) at 60 random points, every value within 1e-9 of the point's unoccluded form
  // factor. Errors of the outline's making are of that form factor's size; the agreement
  // between exact methods is limited by what both take as the shadows: Clipper's grid of
  // 2^-44, and shadows lying past S''s border by the 3D clip's slack (up to 6e-11 of the
  // source's side on these links), which Clipper's union counts and the outline, turning at
  // S''s corners, does not (measured up to 1.5e-10 on a denser grid).
  const std::vector<ProbedLink> links = probedPartialLinks(
      5, {OccluderKind::oneBlocker, OccluderKind::severalBlockers, OccluderKind::slats}, 8);
  ASSERT_EQ(links.size(), 24u);
  std::mt19937_64 random(3);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  std::array<int, 3> unions{};
  double worst = 0.0;
  for (std::size_t k = 0; k < links.size(); ++k) {
    const Link link = links[k].link();
    const Eigen::Vector3d& n = link.receiver.normal;
    ExactVisibility byOutline(link, ShadowUnion::outline), byClipper(link, ShadowUnion::clipper);
    const SourceMoments constant(link.source, 0), quadratic(link.source, 2);
    VisibleRings outline, united;
    // The values at x by both unions (degree 2 too if `withQuadratic`), compared.
    const auto compare = [&](const Eigen::Vector3d& x, bool withQuadratic, const std::string& where) {
      byOutline.visibleRings(x, outline);
      byClipper.visibleRings(x, united);
      expectPiecesCloseUp(outline, where);
      const double unoccluded = pointToPatchFormFactor(x, n, link.source);
      if (!(unoccluded > 0.0)) return;
      std::array<double, 10> a{}, b{};
      a[9] = constant.formFactor(x, n, outline);
      b[9] = constant.formFactor(x, n, united);
      if (withQuadratic) {
        quadratic.compute(x, n, outline, a.data());
        quadratic.compute(x, n, united, b.data());
      }
      for (std::size_t m = 0; m < a.size(); ++m) {
        ASSERT_TRUE(std::isfinite(a[m])) << where;
        const double difference = std::fabs(a[m] - b[m]) / unoccluded;
        EXPECT_LE(difference, 1e-9) << where << " value " << m;
        worst = std::max(worst, difference);
      }
    };
    for (int i = 0; i < 100; ++i) {
      for (int j = 0; j < 100; ++j) {
        compare(link.receiver.pointAt((i + 0.5) / 100, (j + 0.5) / 100), false,
                "link " + std::to_string(k) + " grid " + std::to_string(i) + " " + std::to_string(j));
      }
    }
    for (int point = 0; point < 60; ++point) {
      compare(link.receiver.pointAt(uniform(random), uniform(random)), true,
              "link " + std::to_string(k) + " point " + std::to_string(point));
    }
    const OccluderKind kind = links[k].generated.occluderKind;
    unions[kind == OccluderKind::oneBlocker ? 0 : kind == OccluderKind::severalBlockers ? 1 : 2] +=
        int(byOutline.statistics().unions);
    // The outline closed up everywhere (Clipper took no point in its place).
    EXPECT_EQ(byOutline.statistics().unionsByClipper, 0u) << "link " << k;
  }
  // Shadows overlapped at enough points of several blockers and slats to mean something (a
  // single blocker casts one shadow).
  EXPECT_GT(unions[1], 10000);
  EXPECT_GT(unions[2], 10000);
  std::printf("worst difference %.3g of the unoccluded form factor; points with unions %d %d %d\n",
              worst, unions[0], unions[1], unions[2]);
  RecordProperty("worst_difference", std::to_string(worst));
}

}  // namespace
}  // namespace radquad
