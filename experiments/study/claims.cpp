#include "experiments/study/claims.h"

#include <stdexcept>
#include <string>
#include <vector>

#include "experiments/study/study_metrics.h"

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

// The verdict of "numerator < denominator" from the ratio's interval.
const char* lessVerdict(const PairedRatio& ratio) {
  if (ratio.high < 1.0) return "holds";
  if (ratio.low > 1.0) return "fails";
  return "inconclusive";
}

nlohmann::json comparison(const PairedRatio& ratio, const char* verdict) {
  return {{"ratio", ratio.ratio}, {"low95", ratio.low}, {"high95", ratio.high},
          {"verdict", verdict}};
}

// All hold: holds; any fails: fails; otherwise inconclusive.
const char* overall(const std::vector<std::string>& verdicts) {
  bool all = true;
  for (const std::string& verdict : verdicts) {
    if (verdict == "fails") return "fails";
    all = all && verdict == "holds";
  }
  return all ? "holds" : "inconclusive";
}

}  // namespace

nlohmann::json reportClaims(const nlohmann::json& fig1, const nlohmann::json& fig2, bool vsGold) {
  const std::string suffix = vsGold ? "_vs_gold" : "";
  nlohmann::json out = {{"scored_against", vsGold ? "gold" : "the paper's reference"}};

  // 1. Stratified best on Figure 1.
  {
    const nlohmann::json& perLink = fig1.at("per_link");
    const std::size_t stratified = ruleIndex(fig1, "Stratified");
    const std::vector<double> mine = scores(perLink, "relative_error" + suffix, stratified);
    nlohmann::json against = nlohmann::json::object();
    std::vector<std::string> verdicts;
    for (const nlohmann::json& rule : fig1.at("rules")) {
      const std::string name = rule["name"];
      if (name == "Stratified") continue;
      const PairedRatio ratio =
          pairedRatio(mine, scores(perLink, "relative_error" + suffix, ruleIndex(fig1, name)));
      verdicts.push_back(lessVerdict(ratio));
      against[name] = comparison(ratio, verdicts.back().c_str());
    }
    out["fig1_stratified_best"] = {
        {"claim", "constant bases, partially occluded links: Stratified has the smallest mean "
                  "relative error of K[0][0] (ratio: Stratified / the other rule, paired)"},
        {"links", perLink.size()},
        {"against", against},
        {"verdict", overall(verdicts)}};
  }

  // 2. Gauss far better with quadratic bases.
  {
    nlohmann::json classes = nlohmann::json::object();
    std::vector<std::string> verdicts;
    for (const char* linkClass : {"unoccluded", "partial"}) {
      const nlohmann::json& perLink = fig2.at("classes").at(linkClass).at("per_link");
      const std::vector<double> gauss =
          scores(perLink, "l1_error_bound_total" + suffix, ruleIndex(fig2, "FullGauss"));
      nlohmann::json against = nlohmann::json::object();
      for (const char* other : {"MonteCarlo", "NRook", "Stratified"}) {
        const PairedRatio ratio = pairedRatio(
            gauss, scores(perLink, "l1_error_bound_total" + suffix, ruleIndex(fig2, other)));
        verdicts.push_back(lessVerdict(ratio));
        against[other] = comparison(ratio, verdicts.back().c_str());
      }
      classes[linkClass] = {{"links", perLink.size()}, {"against", against}};
    }
    out["fig2_gauss_best"] = {
        {"claim", "quadratic bases: FullGauss has a smaller mean total L1 bound U_tot than every "
                  "Monte Carlo rule (ratio: FullGauss / the other rule, paired)"},
        {"classes", classes},
        {"verdict", overall(verdicts)}};
  }

  // 3. Partial links carry more error.
  {
    const nlohmann::json& partial = fig2.at("classes").at("partial").at("per_link");
    const nlohmann::json& unoccluded = fig2.at("classes").at("unoccluded").at("per_link");
    nlohmann::json rules = nlohmann::json::object();
    std::vector<std::string> verdicts, scaleFree;
    for (const nlohmann::json& rule : fig2.at("classes").at("partial").at("rules")) {
      const std::string name = rule["name"];
      const std::size_t r = ruleIndex(fig2, name);
      // "unoccluded < partial": the ratio unoccluded / partial below 1.
      const PairedRatio bound = unpairedRatio(scores(unoccluded, "l1_error_bound_total" + suffix, r),
                                              scores(partial, "l1_error_bound_total" + suffix, r));
      const PairedRatio frobenius =
          unpairedRatio(scores(unoccluded, "relative_frobenius_error" + suffix, r),
                        scores(partial, "relative_frobenius_error" + suffix, r));
      verdicts.push_back(lessVerdict(bound));
      scaleFree.push_back(lessVerdict(frobenius));
      rules[name] = {{"l1_error_bound_total", comparison(bound, verdicts.back().c_str())},
                     {"relative_frobenius_error", comparison(frobenius, scaleFree.back().c_str())}};
    }
    out["fig2_partial_more_error"] = {
        {"claim", "partially occluded links carry more error than unoccluded ones, for every "
                  "rule (ratio: unoccluded / partial mean, unpaired)"},
        {"rules", rules},
        {"verdict", overall(verdicts)},
        {"scale_free", {{"metric", "relative_frobenius_error"}, {"verdict", overall(scaleFree)}}}};
  }
  return out;
}

}  // namespace radquad
