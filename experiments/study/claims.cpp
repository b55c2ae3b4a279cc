#include "experiments/study/claims.h"

#include <cstdint>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "experiments/study/study_statistics.h"

namespace radquad {
namespace {

std::size_t ruleIndex(const nlohmann::json& table, const std::string& name) {
  const nlohmann::json& rules =
      table.contains("rules") ? table.at("rules") : table.at("classes").at("partial").at("rules");
  for (std::size_t r = 0; r < rules.size(); ++r) {
    if (rules[r]["name"] == name) return r;
  }
  throw std::runtime_error("claims: rule " + name + " is not in the table");
}

// Every link's score of one rule: per_link[i][key][rule].
std::vector<double> scores(const nlohmann::json& perLink, const std::string& key, std::size_t rule) {
  std::vector<double> out;
  for (const nlohmann::json& link : perLink) out.push_back(link.at(key).at(rule).get<double>());
  return out;
}

std::uint64_t tableSeed(const nlohmann::json& table) {
  return table.at("options").at("seed").get<std::uint64_t>();
}

// The verdict of "numerator < denominator" from the ratio's interval.
const char* lessVerdict(const PairedRatio& ratio) {
  if (ratio.high < 1.0) return "holds";
  if (ratio.low > 1.0) return "fails";
  return "inconclusive";
}

// All hold: holds; any fails: fails; otherwise inconclusive.
std::string overall(const std::vector<std::string>& verdicts) {
  bool all = true;
  for (const std::string& verdict : verdicts) {
    if (verdict == "fails") return "fails";
    all = all && verdict == "holds";
  }
  return all ? "holds" : "inconclusive";
}

// A link of a per-link table: its index there, and its candidate (and scene) when recorded.
nlohmann::json linkName(const nlohmann::json& perLink, std::size_t index) {
  nlohmann::json out = {{"link", index}};
  const nlohmann::json& link = perLink.at(index);
  if (link.contains("candidate")) out["candidate"] = link["candidate"];
  if (link.contains("scene")) out["scene"] = link["scene"];
  return out;
}

// The verdicts of a claim's comparisons, with and without each one's most influential link.
struct Verdicts {
  std::vector<std::string> all, without;
  void add(const nlohmann::json& comparison) {
    all.push_back(comparison["verdict"]);
    without.push_back(comparison["most_influential_link"]["verdict_without"]);
  }
  // The claim's verdict, its verdict without the comparisons' most influential links, and
  // whether they differ (fragile).
  void into(nlohmann::json& claim, const char* prefix = "") const {
    const std::string verdict = overall(all), withoutVerdict = overall(without);
    claim[std::string(prefix) + "verdict"] = verdict;
    claim[std::string(prefix) + "verdict_without_most_influential_links"] = withoutVerdict;
    claim[std::string(prefix) + "fragile"] = verdict != withoutVerdict;
  }
};

nlohmann::json ratioJson(const PairedRatio& ratio) {
  return {{"ratio", ratio.ratio}, {"low95", ratio.low}, {"high95", ratio.high},
          {"verdict", lessVerdict(ratio)}};
}

// An influential link's entry with the comparison redone without it.
nlohmann::json withoutIt(nlohmann::json link, const PairedRatio& rest) {
  link["ratio_without"] = rest.ratio;
  link["low95_without"] = rest.low;
  link["high95_without"] = rest.high;
  link["verdict_without"] = lessVerdict(rest);
  return link;
}

// "a < b" on the same links: the ratio of means with its bootstrap interval, the sign test,
// and the most influential link with the comparison redone without it.
nlohmann::json pairedComparison(const std::vector<double>& a, const std::vector<double>& b,
                                const nlohmann::json& perLink, std::uint64_t seed) {
  nlohmann::json out = ratioJson(pairedRatio(a, b, seed));
  const SignTest sign = signTest(a, b);
  out["links_below"] = sign.below;
  out["links_above"] = sign.above;
  out["links_tied"] = sign.ties;
  out["sign_test_p"] = sign.pValue;
  const Influence influence = mostInfluentialPaired(a, b);
  const PairedRatio rest = pairedRatio(without(a, influence.index), without(b, influence.index), seed);
  nlohmann::json link = linkName(perLink, influence.index);
  link["share_of_numerator"] = influence.shareOfNumerator;
  link["share_of_denominator"] = influence.shareOfDenominator;
  out["most_influential_link"] = withoutIt(std::move(link), rest);
  return out;
}

// "mean(a) < mean(b)" on different links (classes `aName` and `bName`).
nlohmann::json unpairedComparison(const std::vector<double>& a, const std::vector<double>& b,
                                  const nlohmann::json& aLinks, const nlohmann::json& bLinks,
                                  const char* aName, const char* bName, std::uint64_t seed) {
  nlohmann::json out = ratioJson(unpairedRatio(a, b, seed));
  const Influence influence = mostInfluentialUnpaired(a, b);
  const bool inB = influence.inDenominator;
  const PairedRatio rest = inB ? unpairedRatio(a, without(b, influence.index), seed)
                               : unpairedRatio(without(a, influence.index), b, seed);
  nlohmann::json link = linkName(inB ? bLinks : aLinks, influence.index);
  link["class"] = inB ? bName : aName;
  link["share_of_its_class"] = inB ? influence.shareOfDenominator : influence.shareOfNumerator;
  out["most_influential_link"] = withoutIt(std::move(link), rest);
  return out;
}

}  // namespace

nlohmann::json reportClaims(const nlohmann::json& fig1, const nlohmann::json& fig2, bool vsGold) {
  const std::string suffix = vsGold ? "_vs_gold" : "";
  nlohmann::json out = {{"scored_against", vsGold ? "gold" : "the paper's reference"},
                        {"interval", "bootstrap over links, " +
                                         std::to_string(kBootstrapResamples) +
                                         " resamples, 2.5% and 97.5% percentiles"}};

  // 1. Stratified best on Figure 1 (partial links: class 1).
  {
    const nlohmann::json& perLink = fig1.at("per_link");
    const std::uint64_t seed = bootstrapSeed(tableSeed(fig1), 1);
    const std::string key = "relative_error" + suffix;
    const std::vector<double> mine = scores(perLink, key, ruleIndex(fig1, "Stratified"));
    nlohmann::json against = nlohmann::json::object();
    Verdicts verdicts;
    for (const nlohmann::json& rule : fig1.at("rules")) {
      const std::string name = rule["name"];
      if (name == "Stratified") continue;
      against[name] =
          pairedComparison(mine, scores(perLink, key, ruleIndex(fig1, name)), perLink, seed);
      verdicts.add(against[name]);
    }
    nlohmann::json claim = {
        {"claim", "constant bases, partially occluded links: Stratified has the smallest mean "
                  "relative error of K[0][0] (ratio: Stratified / the other rule, paired)"},
        {"links", perLink.size()},
        {"against", against}};
    verdicts.into(claim);
    out["fig1_stratified_best"] = claim;
  }

  // 2. Gauss far better with quadratic bases.
  {
    nlohmann::json classes = nlohmann::json::object();
    Verdicts verdicts;
    for (const auto& [linkClass, classIndex] : {std::pair{"unoccluded", 0}, std::pair{"partial", 1}}) {
      const nlohmann::json& perLink = fig2.at("classes").at(linkClass).at("per_link");
      const std::uint64_t seed = bootstrapSeed(tableSeed(fig2), std::uint64_t(classIndex));
      const std::string key = "l1_error_bound_total" + suffix;
      const std::vector<double> gauss = scores(perLink, key, ruleIndex(fig2, "FullGauss"));
      nlohmann::json against = nlohmann::json::object();
      for (const char* other : {"MonteCarlo", "NRook", "Stratified"}) {
        against[other] =
            pairedComparison(gauss, scores(perLink, key, ruleIndex(fig2, other)), perLink, seed);
        verdicts.add(against[other]);
      }
      classes[linkClass] = {{"links", perLink.size()}, {"against", against}};
    }
    nlohmann::json claim = {
        {"claim", "quadratic bases: FullGauss has a smaller mean total L1 bound U_tot than every "
                  "Monte Carlo rule (ratio: FullGauss / the other rule, paired)"},
        {"classes", classes}};
    verdicts.into(claim);
    out["fig2_gauss_best"] = claim;
  }

  // 3. Partial links carry more error (the two classes resampled independently, from the
  // partial class's seed).
  {
    const nlohmann::json& partial = fig2.at("classes").at("partial").at("per_link");
    const nlohmann::json& unoccluded = fig2.at("classes").at("unoccluded").at("per_link");
    const std::uint64_t seed = bootstrapSeed(tableSeed(fig2), 1);
    nlohmann::json rules = nlohmann::json::object();
    Verdicts bound, scaleFree;
    for (const nlohmann::json& rule : fig2.at("classes").at("partial").at("rules")) {
      const std::string name = rule["name"];
      const std::size_t r = ruleIndex(fig2, name);
      // "unoccluded < partial": the ratio unoccluded / partial below 1.
      nlohmann::json entry;
      for (const char* metric : {"l1_error_bound_total", "relative_frobenius_error"}) {
        entry[metric] = unpairedComparison(scores(unoccluded, metric + suffix, r),
                                           scores(partial, metric + suffix, r), unoccluded,
                                           partial, "unoccluded", "partial", seed);
      }
      bound.add(entry["l1_error_bound_total"]);
      scaleFree.add(entry["relative_frobenius_error"]);
      rules[name] = entry;
    }
    nlohmann::json claim = {
        {"claim", "partially occluded links carry more error than unoccluded ones, for every "
                  "rule (ratio: unoccluded / partial mean, unpaired)"},
        {"rules", rules}};
    bound.into(claim);
    nlohmann::json free = {{"metric", "relative_frobenius_error"}};
    scaleFree.into(free);
    claim["scale_free"] = free;
    out["fig2_partial_more_error"] = claim;
  }
  return out;
}

}  // namespace radquad
