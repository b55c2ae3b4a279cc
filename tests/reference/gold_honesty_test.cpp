// The exact gold's error estimate on the study's own links: over the partial links the
// study's generator draws (one blocker, several blockers, slats; the soups take the dense
// gold), at degrees 0 and 2, the Genz-Malik gold at the study's tolerance is compared with a
// gold 3,000 times tighter by the critical lines (an outer integration of its own). Every
// coefficient's actual error must stay below the estimate. Label "accuracy".
// Where an occluder stands on the receiver the inner integral jumps, and the default takes the
// jump lines instead of Genz-Malik, whose estimate misjudges the jump (the second test).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <memory>
#include <vector>

#include "experiments/scenarios/probed_links.h"
#include "reference/critical_segments.h"
#include "reference/exact_gold.h"
#include "reference/exact_visibility.h"

namespace radquad {
namespace {

struct Tally {
  int failures = 0;
  double worstRatio = 0.0;  // actual error / (estimate + the truth's estimate)
  double worstError = 0.0;  // actual error / max |K|
  std::uint64_t points = 0;
};

// The Genz-Malik gold with `options` on every link against `truths`.
Tally tally(const std::vector<Link>& links, const std::vector<ExactGold>& truths, int degree,
            const ExactGoldOptions& options) {
  Tally out;
  for (std::size_t k = 0; k < links.size(); ++k) {
    const ExactGold gold = exactGold(links[k], degree, options);
    const ExactGold& truth = truths[k];
    EXPECT_TRUE(gold.converged) << "link " << k;
    const double largest = truth.coupling.cwiseAbs().maxCoeff();
    bool failed = false;
    for (Eigen::Index a = 0; a < gold.coupling.size(); ++a) {
      const double actual = std::abs(gold.coupling.data()[a] - truth.coupling.data()[a]);
      const double allowed = gold.couplingError.data()[a] + truth.couplingError.data()[a];
      out.worstRatio = std::max(out.worstRatio, actual / std::max(allowed, 1e-300));
      out.worstError = std::max(out.worstError, actual / largest);
      failed = failed || actual > allowed;
    }
    out.failures += failed;
    out.points += gold.receiverPoints;
  }
  return out;
}

TEST(GoldHonesty, GenzMalikErrorEstimatesHoldOnTheStudysLinks) {
  // 24 links (8 of each kind); the truths by the other outer method, the critical lines,
  // whatever their breakpoints cost, at 1e-7 or as near as 600,000 receiver points take
  // them (on two of these links Genz-Malik does not reach 1e-7 in 4,000,000 points).
  // The first 8 partial links of each kind drawn from seed 5, as the study keeps them.
  const std::vector<ProbedLink> links = probedPartialLinks(
      5, {OccluderKind::oneBlocker, OccluderKind::severalBlockers, OccluderKind::slats}, 8);
  ASSERT_EQ(links.size(), 24u);
  std::vector<Link> views;
  for (const ProbedLink& drawn : links) views.push_back(drawn.link());
  for (int degree : {0, 2}) {
    SCOPED_TRACE(degree);
    std::vector<ExactGold> truths;
    for (const ProbedLink& drawn : links) {
      ExactGoldOptions tight;
      tight.tolerance = 1e-7;
      tight.maxFloorPoints = tight.maxFloorPointsHigherDegrees = 1ull << 40;
      tight.maxEvaluations = 600000;
      // At degree 2 the gold checked integrates the unoccluded part apart (exact_gold.h);
      // the truths integrate S' minus the shadows at every point, another integrand.
      tight.unoccludedApart = false;
      truths.push_back(exactGold(drawn.link(), degree, tight));
      // A truth may stop at its budget: its own estimate still counts, and it must be a
      // hundred times below the tolerance checked.
      const ExactGold& truth = truths.back();
      EXPECT_LE(truth.couplingError.maxCoeff(), 3e-6 * truth.coupling.cwiseAbs().maxCoeff());
      ASSERT_EQ(truths.back().outer, ExactOuterMethod::criticalLines);
    }
    ExactGoldOptions study;
    study.tolerance = 3e-4;
    study.outer = ExactOuterMethod::genzMalik;
    const Tally grid = tally(views, truths, degree, study);
    std::printf("degree %d, initial grid %d: %d of %zu links failed; worst actual error %.3g of "
                "the estimate, %.3g of max |K|; %.0f receiver points per link\n",
                degree, study.initialGrid, grid.failures, links.size(), grid.worstRatio,
                grid.worstError, double(grid.points) / double(links.size()));
    EXPECT_EQ(grid.failures, 0);
    // The study's own choice of outer integration (critical lines, jump lines or Genz-Malik).
    ExactGoldOptions automatic;
    automatic.tolerance = study.tolerance;
    const Tally chosen = tally(views, truths, degree, automatic);
    std::printf("degree %d, default outer integration: %d of %zu links failed; worst actual "
                "error %.3g of the estimate\n",
                degree, chosen.failures, links.size(), chosen.worstRatio);
    EXPECT_EQ(chosen.failures, 0);
    // The check has teeth: started from the whole square, a run misses a shadow on at least
    // one of these links and reports an error below the one it makes (integrating S' minus
    // the shadows at every point; with the unoccluded part apart, no link failed at degree 2).
    ExactGoldOptions lone = study;
    lone.initialGrid = 1;
    lone.unoccludedApart = false;
    const Tally blind = tally(views, truths, degree, lone);
    std::printf("degree %d, initial grid 1: %d of %zu links failed; worst actual error %.3g of "
                "the estimate\n",
                degree, blind.failures, links.size(), blind.worstRatio);
    EXPECT_GE(blind.failures, 1);
  }
}

TEST(GoldHonesty, WhereAnOccluderStandsOnTheReceiverTheJumpLinesKeepTheirEstimate) {
  // Slats link 15 of seed 11, as the study keeps them: two slats meet the receiver, so the
  // inner integral jumps along two segments, and the critical segments (247) are too many for
  // their breakpoints. Against a critical-line gold at 1e-6, Genz-Malik at the study's 3e-4
  // ended with an actual error 1.2 (degree 0) and 5.3 (degree 2) times its estimate; the
  // default takes the jump lines and must stay within its own.
  const std::vector<ProbedLink> drawn = probedPartialLinks(11, {OccluderKind::slats}, 16);
  ASSERT_EQ(drawn.size(), 16u);
  const Link link = drawn[15].link();
  const ExactVisibility visibility(link);
  ASSERT_FALSE(contactSegments(link.receiver, visibility.candidates()).empty());
  for (int degree : {0, 2}) {
    SCOPED_TRACE(degree);
    ExactGoldOptions tight;
    tight.tolerance = 1e-6;
    tight.maxFloorPoints = tight.maxFloorPointsHigherDegrees = 1ull << 40;
    tight.unoccludedApart = false;  // another integrand than the default's at degree 2
    const ExactGold truth = exactGold(link, degree, tight);
    ASSERT_EQ(truth.outer, ExactOuterMethod::criticalLines);
    ASSERT_TRUE(truth.converged);
    ExactGoldOptions study;
    study.tolerance = 3e-4;
    const ExactGold gold = exactGold(link, degree, study);
    EXPECT_EQ(gold.outer, ExactOuterMethod::jumpLines);
    EXPECT_TRUE(gold.converged);
    const Tally jump = tally({link}, {truth}, degree, study);
    std::printf("degree %d, jump lines: worst actual error %.3g of the estimate, %.3g of max |K|; "
                "%llu receiver points\n",
                degree, jump.worstRatio, jump.worstError, (unsigned long long)jump.points);
    EXPECT_EQ(jump.failures, 0);
    study.outer = ExactOuterMethod::genzMalik;
    const Tally blind = tally({link}, {truth}, degree, study);
    std::printf("degree %d, genz-malik: worst actual error %.3g of the estimate\n", degree,
                blind.worstRatio);
    // The check has teeth where Genz-Malik's miss is largest.
    if (degree == 2) {
      EXPECT_EQ(blind.failures, 1);
    }
  }
}

}  // namespace
}  // namespace radquad
