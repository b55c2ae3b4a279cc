// The exact gold never reports less error than it has, at any tolerance from the study's 3e-4
// to 1e-9: on the honesty suite (tests/reference/honesty_links.h: 25 partially occluded links
// of each of four kinds, slats, crossed slats, small far sources, overlapping blockers), every
// gold the default method chooses is compared with a run 1,000 times tighter (relative to the
// larger of its tolerance and its reported error, and no tighter than 1e-12) by the other
// outer method: the critical lines for Genz-Malik and jump-line golds, the jump lines (no
// critical segments as breakpoints; confirmed by a second run below 1e-4) for critical-line
// golds. Every coefficient's difference must lie within the two runs' summed estimates. At
// degree 0 every link at 3e-4, 1e-5, 1e-7 and 1e-9; at degree 2 the first 5 links of each
// kind at 3e-4 and 1e-7. Label "honesty" (long: tens of minutes on two cores).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <map>
#include <string>
#include <vector>

#include "reference/exact_gold.h"
#include "tests/reference/honesty_links.h"

namespace radquad {
namespace {

struct Summary {
  int golds = 0, unconverged = 0, failures = 0, sharp = 0;
  double worst = 0.0;  // actual / (gold's estimate + truth's estimate)
  std::map<std::string, int> methods;
};

double relativeError(const ExactGold& gold) {
  return gold.couplingError.maxCoeff() / gold.coupling.cwiseAbs().maxCoeff();
}

// The truth for golds by `method`: the other outer method at `tolerance`, integrating S' minus
// the shadows at every point (the golds at degree >= 1 integrate the unoccluded part apart).
ExactGold truthFor(const Link& link, int degree, ExactOuterMethod method, double tolerance) {
  ExactGoldOptions options;
  options.tolerance = tolerance;
  options.unoccludedApart = false;
  options.maxEvaluations = 4000000;
  if (method == ExactOuterMethod::criticalLines) {
    options.outer = ExactOuterMethod::jumpLines;
  } else {
    options.outer = ExactOuterMethod::criticalLines;
    options.maxFloorPoints = options.maxFloorPointsHigherDegrees = 1ull << 40;
  }
  return exactGold(link, degree, options);
}

void check(const std::vector<HonestyLink>& links, int degree, const std::vector<double>& tolerances,
           std::map<double, Summary>& summaries) {
  for (const HonestyLink& drawn : links) {
    const Link link = drawn.link();
    std::vector<ExactGold> golds;
    // The tightest truth each method's golds need.
    std::map<bool, double> needed;  // keyed by "the gold took the critical lines"
    for (const double tolerance : tolerances) {
      ExactGoldOptions options;
      options.tolerance = tolerance;
      golds.push_back(exactGold(link, degree, options));
      const bool lines = golds.back().outer == ExactOuterMethod::criticalLines;
      const double wanted = std::max(1e-12, 1e-3 * std::max(tolerance, relativeError(golds.back())));
      needed[lines] = needed.count(lines) ? std::min(needed[lines], wanted) : wanted;
    }
    std::map<bool, ExactGold> truths;
    for (const auto& [lines, tolerance] : needed) {
      truths[lines] = truthFor(
          link, degree, lines ? ExactOuterMethod::criticalLines : ExactOuterMethod::genzMalik,
          tolerance);
    }
    for (std::size_t t = 0; t < tolerances.size(); ++t) {
      const ExactGold& gold = golds[t];
      const ExactGold& truth = truths[gold.outer == ExactOuterMethod::criticalLines];
      EXPECT_NE(truth.outer, gold.outer);
      Summary& summary = summaries[tolerances[t]];
      ++summary.golds;
      ++summary.methods[exactOuterMethodName(gold.outer)];
      summary.unconverged += gold.converged ? 0 : 1;
      summary.sharp += relativeError(truth) <= 0.1 * relativeError(gold) ? 1 : 0;
      double worst = 0.0;
      for (Eigen::Index k = 0; k < gold.coupling.size(); ++k) {
        const double actual = std::abs(gold.coupling.data()[k] - truth.coupling.data()[k]);
        worst = std::max(worst, actual / (gold.couplingError.data()[k] + truth.couplingError.data()[k]));
      }
      summary.worst = std::max(summary.worst, worst);
      summary.failures += worst > 1.0 ? 1 : 0;
      EXPECT_LE(worst, 1.0) << honestyKindName(drawn.kind) << " candidate " << drawn.candidate
                            << ", degree " << degree << ", tolerance " << tolerances[t] << ", "
                            << exactOuterMethodName(gold.outer) << " against "
                            << exactOuterMethodName(truth.outer);
    }
  }
}

void print(int degree, const std::map<double, Summary>& summaries) {
  for (const auto& [tolerance, summary] : summaries) {
    std::printf("degree %d, tolerance %.0e: %d golds (", degree, tolerance, summary.golds);
    for (const auto& [method, count] : summary.methods) std::printf(" %s %d", method.c_str(), count);
    std::printf(" ), %d unconverged, %d with a truth estimated 10 times tighter; worst actual "
                "error %.3g of the two estimates; %d failed\n",
                summary.unconverged, summary.sharp, summary.worst, summary.failures);
  }
}

TEST(GoldHonestySuite, EveryEstimateHoldsAgainstAThousandTimesTighterRunByTheOtherMethod) {
  const std::vector<HonestyLink> links = honestyLinks(46, 25);
  ASSERT_EQ(links.size(), 100u);
  std::map<double, Summary> zero;
  check(links, 0, {3e-4, 1e-5, 1e-7, 1e-9}, zero);
  print(0, zero);
  std::vector<HonestyLink> few;
  for (int kind = 0; kind < 4; ++kind) {
    for (int k = 0; k < 5; ++k) {
      const HonestyLink& drawn = links[std::size_t(25 * kind + k)];
      few.push_back({drawn.kind, drawn.candidate, drawn.geometry, drawn.geometry.occluderScene()});
    }
  }
  std::map<double, Summary> two;
  check(few, 2, {3e-4, 1e-7}, two);
  print(2, two);
}

}  // namespace
}  // namespace radquad
