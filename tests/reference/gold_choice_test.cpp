// Which gold a link takes, decided by its geometry (reference/gold_reference.h): the shaft
// test, thin shadows that sample rays miss, the methods asked for, singular links; and the
// exact gold's confirmation of its error where its outer rules can be fooled together.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include "kernel/occluder_scene.h"
#include "kernel/patch_intersection.h"
#include "quadrature/gauss_legendre.h"
#include "quadrature/prepared_rule.h"
#include "quadrature/rules/gauss_product.h"
#include "reference/exact_gold.h"
#include "reference/exact_visibility.h"
#include "reference/gold_reference.h"
#include "tests/support/analytic_form_factors.h"

namespace radquad {
namespace {

const Patch kFloor = Patch::make({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, "floor");
const Patch kCeiling = Patch::make({0, 1, 1}, {1, 0, 0}, {0, -1, 0}, "ceiling");

// The largest gap between the x coordinates, at height 1/2, of the rays of the n^4 Gauss
// products for n = 4 and 8 between the unit squares z = 0 and z = 1: (s + u) / 2.
std::pair<double, double> widestGapBetweenGaussRays() {
  std::vector<double> xs = {0.0, 1.0};
  for (const int n : {4, 8}) {
    const GaussLegendreRule& rule = gaussLegendreUnit(n);
    for (const double s : rule.nodes) {
      for (const double u : rule.nodes) xs.push_back(0.5 * (s + u));
    }
  }
  std::sort(xs.begin(), xs.end());
  std::pair<double, double> widest{0.0, 0.0};
  for (std::size_t k = 1; k < xs.size(); ++k) {
    if (xs[k] - xs[k - 1] > widest.second - widest.first) widest = {xs[k - 1], xs[k]};
  }
  return widest;
}

TEST(GoldChoice, AThinShadowThatGaussRaysMissTakesTheExactGold) {
  // A strip along y at height 1/2 between the opposed unit squares, a quarter as wide as the
  // widest gap between the Gauss products' rays there: no ray of the 4^4 and 8^4 products is
  // blocked (a choice by sample rays took such links for unoccluded, with an error of about
  // 0), yet it hides part of the source from every receiver point.
  const auto [low, high] = widestGapBetweenGaussRays();
  const double width = 0.25 * (high - low);
  OccluderScene scene;
  scene.addParallelogram(
      Patch::make({0.5 * (low + high) - 0.5 * width, -0.1, 0.5}, {width, 0, 0}, {0, 1.2, 0}, "strip"));
  scene.commit();
  const Link link{kFloor, kCeiling, &scene};
  CouplingAccumulator accumulator;
  for (const int n : {4, 8}) {
    const PreparedRule gauss(std::make_shared<GaussProductRule>(GaussPointCounts{n, n, n, n}), 0);
    LinkIntegral integral;
    gauss.integrate(link, 0, accumulator, integral);
    ASSERT_EQ(integral.raysBlocked, 0u) << n;
  }
  EXPECT_EQ(ExactVisibility(link).occludersInShaft(), 1u);
  const GoldReference gold = goldReference(link, 0, 0);
  EXPECT_EQ(gold.method, "exact visibility");
  EXPECT_TRUE(gold.converged);
  EXPECT_GT(gold.couplingError(0, 0), 0.0);
  // The shadow is there: the form factor is below the unoccluded one (Howell C-11) by far
  // more than the gold's error.
  const double unoccluded = analytic::parallelRectangles(1, 1, 1);
  EXPECT_LT(gold.formFactor, unoccluded - 100.0 * gold.formFactorError);
}

TEST(GoldChoice, TheShaftTestCountsWhatMeetsTheShaftsInterior) {
  const auto count = [](const std::vector<Patch>& occluders) {
    OccluderScene scene;
    for (const Patch& patch : occluders) scene.addParallelogram(patch);
    scene.commit();
    return ExactVisibility(Link{kFloor, kCeiling, &scene}).occludersInShaft();
  };
  // A neighbour of the receiver in its plane, sharing its edge: it touches the shaft only.
  EXPECT_EQ(count({Patch::make({1, 0, 0}, {1, 0, 0}, {0, 1, 0}, "neighbour")}), 0u);
  // A wall along the shaft's side face x = 1, outside it; one a hair inside meets it.
  EXPECT_EQ(count({Patch::make({1, 0, 0}, {0, 1, 0}, {0, 0, 1}, "side")}), 0u);
  EXPECT_EQ(count({Patch::make({1 - 1e-6, 0, 0}, {0, 1, 0}, {0, 0, 1}, "inside")}), 1u);
  // Beyond the source, and a small blocker in the middle.
  EXPECT_EQ(count({Patch::make({0, 0, 2}, {1, 0, 0}, {0, 1, 0}, "above")}), 0u);
  EXPECT_EQ(count({Patch::make({0.4, 0.4, 0.5}, {0.01, 0, 0}, {0, 0.01, 0}, "speck")}), 1u);
  // A polygon outside the shaft that no face plane of it separates: beyond the edge where the
  // side faces x = 1 and y = 0 meet, on the far side of the line x - y = 1.2 at height 1/2.
  // The conservative cull keeps it; the shaft test does not count it.
  const Patch corner = Patch::make({0.9, -0.3, 0.5}, {0.4, 0.4, 0}, {0.4, 0, 0}, "corner");
  OccluderScene scene;
  scene.addParallelogram(corner);
  scene.commit();
  const ExactVisibility visibility(Link{kFloor, kCeiling, &scene});
  EXPECT_EQ(visibility.candidateCount(), 1u);
  EXPECT_EQ(visibility.occludersInShaft(), 0u);
}

TEST(GoldChoice, EveryMethodAskedForIsHonoured) {
  // Two blockers; with maxExactOccluders 1, the default (auto) takes the dense gold for their
  // link; `exact` takes exact visibility anyway, on an unoccluded link too, and `stratified`
  // the dense gold on both.
  OccluderScene scene;
  scene.addParallelogram(Patch::make({0.1, 0.1, 0.4}, {0.3, 0, 0}, {0, 0.3, 0}, "a"));
  scene.addParallelogram(Patch::make({0.6, 0.5, 0.6}, {0.3, 0, 0}, {0, 0.3, 0}, "b"));
  scene.commit();
  const Link occluded{kFloor, kCeiling, &scene};
  const Link unoccluded{kFloor, kCeiling, nullptr};
  GoldOptions options;
  options.maxExactOccluders = 1;
  options.denseStrata = 8;
  options.denseReplicates = 4;
  EXPECT_EQ(goldReference(occluded, 0, 0, options).method, "dense stratified");
  EXPECT_EQ(goldReference(unoccluded, 0, 0, options).method, "gauss product");
  options.method = GoldMethod::exact;
  const GoldReference exact = goldReference(occluded, 0, 0, options);
  EXPECT_EQ(exact.method, "exact visibility");
  const GoldReference exactUnoccluded = goldReference(unoccluded, 0, 0, options);
  EXPECT_EQ(exactUnoccluded.method, "exact visibility");
  const double expected = analytic::parallelRectangles(1, 1, 1);
  EXPECT_NEAR(exactUnoccluded.formFactor, expected, 1e-7 * expected);
  options.method = GoldMethod::stratified;
  EXPECT_EQ(goldReference(occluded, 0, 0, options).method, "dense stratified");
  EXPECT_EQ(goldReference(unoccluded, 0, 0, options).method, "dense stratified");
  EXPECT_EQ(parseGoldMethod("auto", "test"), GoldMethod::automatic);
  EXPECT_STREQ(goldMethodName(GoldMethod::automatic), "auto");
}

// A small source far above a receiver, behind one blocker whose edge sweeps a narrow penumbra
// across the receiver nearly along its s axis (a link of the honesty suite's kind "small far
// source", tests/reference/honesty_links.h, its coordinates rounded).
struct SmallFarSource {
  OccluderScene scene;
  Link link;
  SmallFarSource() {
    const Patch receiver = Patch::make({-0.277286, -0.420707, 0}, {0.554571, 0, 0},
                                       {0, 0.841414, 0}, "receiver");
    const Patch source = Patch::make({-0.160, -0.297, 3.741}, {-0.003, 0.093, -0.019},
                                     {0.060, -0.002, -0.020}, "source");
    scene.addParallelogram(Patch::make({1.165, -0.427, 0.679}, {0.205, 1.208, 0.177},
                                       {-2.441, 0.413, 0.0}, "blocker"));
    scene.commit();
    link = Link{receiver, source, &scene};
  }
};

// max over entries of |a - b| / (a's error + b's error).
double worstAgainst(const ExactGold& gold, const ExactGold& truth) {
  double worst = 0.0;
  for (Eigen::Index k = 0; k < gold.coupling.size(); ++k) {
    worst = std::max(worst, std::abs(gold.coupling.data()[k] - truth.coupling.data()[k]) /
                                (gold.couplingError.data()[k] + truth.couplingError.data()[k]));
  }
  return worst;
}

TEST(GoldChoice, GenzMalikIsConfirmedWhereItsRulesAgreeWhileWrong) {
  const SmallFarSource far;
  ASSERT_GT(far.link.source.normal.dot(far.link.receiver.centre() - far.link.source.centre()), 0.0);
  // The truth: the critical lines (the penumbra's edges as breakpoints), a thousand times
  // tighter.
  ExactGoldOptions tight;
  tight.tolerance = 1e-11;
  const ExactGold truth = exactGold(far.link, 0, tight);
  ASSERT_EQ(truth.outer, ExactOuterMethod::criticalLines);
  ASSERT_TRUE(truth.converged);
  // A lone Genz-Malik run from 8 x 8 regions at 1e-8 misses by more than its estimate: the
  // penumbra's kinks sit at the same place in many regions, whose two rules then agree.
  ExactGoldOptions alone;
  alone.tolerance = 1e-8;
  alone.outer = ExactOuterMethod::genzMalik;
  alone.confirmBelow = 0.0;
  const ExactGold lone = exactGold(far.link, 0, alone);
  EXPECT_TRUE(lone.converged);
  EXPECT_GT(worstAgainst(lone, truth), 1.0);
  // Confirmed by a second run from 11 x 11 regions, its error holds (or it says it did not
  // converge).
  ExactGoldOptions confirmed = alone;
  confirmed.confirmBelow = 1e-4;
  const ExactGold checked = exactGold(far.link, 0, confirmed);
  EXPECT_LE(worstAgainst(checked, truth), 1.0);
  if (!checked.confirmed) {
    EXPECT_FALSE(checked.converged);
  }
  // The critical lines at 1e-9 meet it at their breakpoints, but the gold vouches for no more
  // than a hundredth of its tolerance.
  ExactGoldOptions lines;
  lines.tolerance = 1e-9;
  const ExactGold critical = exactGold(far.link, 0, lines);
  EXPECT_EQ(critical.outer, ExactOuterMethod::criticalLines);
  EXPECT_GE(critical.couplingError.minCoeff(), 1e-11 * critical.coupling.cwiseAbs().maxCoeff());
  EXPECT_LE(worstAgainst(critical, truth), 1.0);
}

}  // namespace
}  // namespace radquad
