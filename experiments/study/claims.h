// The report's claims about its Figures 1 and 2 (Gershbein 1995, section 4), checked on a
// pair of study tables as the report states them, each with a verdict: "holds" (the 95%
// interval of the ratio of means lies on the claimed side of 1), "fails" (on the other side)
// or "inconclusive" (it contains 1). A claim that fails with a correct implementation is a
// finding, recorded as such; the suites are never tuned to make a claim hold.
//
// Intervals are bootstrap intervals over links (study_statistics.h), drawn from the tables'
// seeds (bootstrapSeed), so the claims are the same bits on every run. Every comparison also
// gives the sign test of its per-link differences (paired claims) and its most influential
// link: the one whose removal moves the ratio the most, its share of each sum, and the ratio,
// interval and verdict without it. A claim whose verdict changes when every comparison loses
// its most influential link is `fragile`: one link decides it.
//
// 1. fig1_stratified_best: "stratified sampling performs best" on partially occluded links
//    with constant bases: Stratified's mean relative error of K[0][0] against every other
//    rule's, paired on the same links.
// 2. fig2_gauss_best: with quadratic bases the Gauss rules are "far better": every Monte
//    Carlo rule's mean total L1 bound U_tot against FullGauss's, paired, in each class.
// 3. fig2_partial_more_error: partially occluded links carry more error than unoccluded
//    ones: for each rule, the mean U_tot of the partial class against the unoccluded class's
//    (different links: unpaired). The report states it in U_b; the same ratio in the
//    scale-free relative Frobenius error is recorded beside it (`scale_free`), since U_b
//    follows each link's size of K.
// The per-link scores come from the tables' `per_link` (four significant digits), so a claim's
// ratio can differ from the table's own `ratio_to_fullgauss` (computed at full precision) in
// the fifth digit.
#pragma once

#include <nlohmann/json.hpp>

namespace radquad {

// The rules the claims compare; a table without one of them cannot be checked.
inline constexpr const char* kClaimRules[] = {"Stratified", "FullGauss", "MonteCarlo", "NRook"};

// `fig1` and `fig2` are study tables (schema radquad.study/1) with per-link scores;
// `vsGold` scores against the gold (the tables must then hold gold scores).
nlohmann::json reportClaims(const nlohmann::json& fig1, const nlohmann::json& fig2, bool vsGold);

}  // namespace radquad
