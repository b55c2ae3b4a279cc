// The error tables of Figures 1 and 2 (field meanings: docs/cli.md, "The tables").
#include <cmath>
#include <map>
#include <stdexcept>
#include <string>

#include "experiments/json_input.h"
#include "experiments/study/reference_estimate.h"
#include "experiments/study/study_breakdown.h"
#include "experiments/study/study_link_tables.h"
#include "experiments/study/study_metrics.h"
#include "experiments/study/study_runner.h"
#include "experiments/study/study_statistics.h"

namespace radquad {
namespace {

constexpr const char* kSchema = "radquad.study/1";

std::vector<double> column(const std::vector<LinkRecord>& links, const auto& pick) {
  std::vector<double> values;
  values.reserve(links.size());
  for (const LinkRecord& link : links) values.push_back(pick(link));
  return values;
}

// Mean over links of each source function's bound, and their sum, with the standard error
// of each mean over links (what the CI baselines scale their margins by).
nlohmann::json boundTable(const std::vector<LinkRecord>& links, const auto& pickVector) {
  std::vector<std::vector<double>> perFunction;
  std::vector<double> totals;
  for (const LinkRecord& link : links) {
    const std::vector<double>& values = pickVector(link);
    perFunction.resize(values.size());
    double total = 0.0;
    for (std::size_t b = 0; b < values.size(); ++b) {
      perFunction[b].push_back(values[b]);
      total += values[b];
    }
    totals.push_back(total);
  }
  std::vector<double> means, sems, medians, p90s, maxima;
  for (const auto& values : perFunction) {
    const SummaryStatistics statistics = summarize(values);
    means.push_back(statistics.mean);
    sems.push_back(statistics.sem);
    medians.push_back(statistics.median);
    p90s.push_back(statistics.p90);
    maxima.push_back(statistics.max);
  }
  double total = 0.0;
  for (const double mean : means) total += mean;
  const SummaryStatistics totalStatistics = summarize(totals);
  return {{"per_source_function", means},
          {"total", total},
          {"per_source_function_sem", sems},
          {"total_sem", totalStatistics.sem},
          {"per_source_function_median", medians},
          {"per_source_function_p90", p90s},
          {"per_source_function_max", maxima},
          {"total_median", totalStatistics.median},
          {"total_p90", totalStatistics.p90},
          {"total_max", totalStatistics.max},
          {"total_largest_share", totalStatistics.largestShare}};
}

nlohmann::json standardErrorSummary(const std::vector<LinkRecord>& links) {
  const auto values =
      column(links, [](const LinkRecord& l) { return l.referenceRelativeStandardError; });
  if (values.empty() || std::isnan(values.front())) return {{"mean", nullptr}, {"max", nullptr}};
  const SummaryStatistics statistics = summarize(values);
  return {{"mean", statistics.mean}, {"max", statistics.max}};
}

nlohmann::json candidateCounts(const ClassRun& run) {
  std::map<std::string, int> byOccluder, byOrientation;
  for (const LinkRecord& link : run.links) {
    ++byOccluder[occluderKindName(link.occluderKind)];
    ++byOrientation[orientationName(link.orientation)];
  }
  nlohmann::json counts = {{"generated", run.generated},
                            {"accepted", run.links.size()},
                            {"rejected_mostly_visible", run.rejectedMostlyVisible},
                            {"rejected_mostly_blocked", run.rejectedMostlyBlocked},
                            {"rejected_occluder_crosses_patch", run.rejectedOccluderCrossesPatch},
                            {"reference_rays", run.referenceRays},
                            {"accepted_by_occluder", byOccluder},
                            {"accepted_by_orientation", byOrientation}};
  if (run.available > 0) {
    counts["scene_links_in_pool"] = run.available;
    counts["by_own_class"] = run.candidatesByOwnClass;
    counts["refused_unconverged_gold"] = run.refusedGoldCandidates.size();
    counts["refused_gold_candidates"] = run.refusedGoldCandidates;
  }
  return counts;
}

// The index of FullGauss among the run's rules, -1 when it is not scored.
int fullGaussIndex(const StudyRun& run) {
  for (std::size_t r = 0; r < run.rules.size(); ++r) {
    if (run.rules[r].name == "FullGauss") return int(r);
  }
  return -1;
}

// {ratio, low, high} of rule r's mean score to FullGauss's on the same links, the interval by
// the class's bootstrap over links (study_statistics.h), and the sign test of the per-link
// differences (links where the rule's score is below FullGauss's, above, tied; p-value).
nlohmann::json ratioToFullGauss(const std::vector<LinkRecord>& links, std::size_t r, int fullGauss,
                                std::uint64_t seed, const auto& pick) {
  std::vector<double> rule, base;
  for (const LinkRecord& link : links) {
    rule.push_back(pick(link, r));
    base.push_back(pick(link, std::size_t(fullGauss)));
  }
  const PairedRatio ratio = pairedRatio(rule, base, seed);
  const SignTest sign = signTest(rule, base);
  return {{"ratio", ratio.ratio}, {"low95", ratio.low}, {"high95", ratio.high},
          {"links_below", sign.below}, {"links_above", sign.above}, {"links_tied", sign.ties},
          {"sign_test_p", sign.pValue}};
}

// The gold's own mean error over the rule's mean error against the gold, per metric of the
// figure: a bar is measured, not noise, when this share is small (below kGoldNoiseLimit).
constexpr double kGoldNoiseLimit = 0.01;

double meanOf(const std::vector<LinkRecord>& links, double (*pick)(const LinkRecord&, std::size_t),
              std::size_t r) {
  double total = 0.0;
  for (const LinkRecord& link : links) total += pick(link, r);
  return total / double(links.size());
}

nlohmann::json goldNoiseShare(const std::vector<LinkRecord>& links, std::size_t r, bool fig2) {
  // null where the share is not a finite number (a rule exactly on the gold while the gold
  // has an error of its own): the check then fails.
  const auto share = [&](double (*own)(const LinkRecord&, std::size_t),
                         double (*rule)(const LinkRecord&, std::size_t)) -> nlohmann::json {
    const double ownMean = meanOf(links, own, r), ruleMean = meanOf(links, rule, r);
    if (ownMean == 0.0) return 0.0;
    const double value = ownMean / ruleMean;
    return std::isfinite(value) ? nlohmann::json(value) : nlohmann::json(nullptr);
  };
  nlohmann::json out = {
      {"relative_error", share([](const LinkRecord& l, std::size_t) { return std::abs(l.goldRelativeError); },
                               [](const LinkRecord& l, std::size_t k) { return l.relativeErrorVsGold[k]; })}};
  if (fig2) {
    out["l1_error_bound_total"] =
        share([](const LinkRecord& l, std::size_t) { return l.goldL1BoundTotal; },
              [](const LinkRecord& l, std::size_t k) { return sum(l.l1BoundVsGold[k]); });
    out["relative_frobenius_error"] =
        share([](const LinkRecord& l, std::size_t) { return l.goldFrobeniusError; },
              [](const LinkRecord& l, std::size_t k) { return l.frobeniusErrorVsGold[k]; });
  }
  return out;
}

nlohmann::json ruleEntry(const StudyRun& run, std::size_t r, const ClassRun& classRun, bool gold,
                         bool fig2, std::uint64_t seed) {
  const RuleInfo& rule = run.rules[r];
  const auto& links = classRun.links;
  nlohmann::json entry = {
      {"name", rule.name},
      {"samples", rule.samples},
      {"kernel_evaluations", rule.samples},
      {"random", rule.random},
      {"trials", rule.trials},
      {"relative_error", statisticsToJson(summarize(column(
                             links, [r](const LinkRecord& l) { return l.relativeError[r]; })))}};
  const int fullGauss = fullGaussIndex(run);
  const auto pickRelative = [](const LinkRecord& l, std::size_t k) { return l.relativeError[k]; };
  nlohmann::json ratios = nlohmann::json::object();
  if (fullGauss >= 0 && !links.empty()) {
    ratios["relative_error"] = ratioToFullGauss(links, r, fullGauss, seed, pickRelative);
  }
  if (fig2) {
    entry["l1_error_bound"] = boundTable(
        links, [r](const LinkRecord& l) -> const std::vector<double>& { return l.l1Bound[r]; });
    entry["relative_frobenius_error"] = statisticsToJson(
        summarize(column(links, [r](const LinkRecord& l) { return l.frobeniusError[r]; })));
    if (fullGauss >= 0 && !links.empty()) {
      ratios["l1_error_bound_total"] = ratioToFullGauss(
          links, r, fullGauss, seed, [](const LinkRecord& l, std::size_t k) { return sum(l.l1Bound[k]); });
      ratios["relative_frobenius_error"] = ratioToFullGauss(
          links, r, fullGauss, seed, [](const LinkRecord& l, std::size_t k) { return l.frobeniusError[k]; });
    }
  }
  if (gold) {
    entry["relative_error_vs_gold"] = statisticsToJson(
        summarize(column(links, [r](const LinkRecord& l) { return l.relativeErrorVsGold[r]; })));
    if (fullGauss >= 0 && !links.empty()) {
      ratios["relative_error_vs_gold"] = ratioToFullGauss(
          links, r, fullGauss, seed, [](const LinkRecord& l, std::size_t k) { return l.relativeErrorVsGold[k]; });
    }
    if (fig2) {
      entry["l1_error_bound_vs_gold"] = boundTable(
          links,
          [r](const LinkRecord& l) -> const std::vector<double>& { return l.l1BoundVsGold[r]; });
      entry["relative_frobenius_error_vs_gold"] = statisticsToJson(summarize(
          column(links, [r](const LinkRecord& l) { return l.frobeniusErrorVsGold[r]; })));
      if (fullGauss >= 0 && !links.empty()) {
        ratios["l1_error_bound_total_vs_gold"] =
            ratioToFullGauss(links, r, fullGauss, seed, [](const LinkRecord& l, std::size_t k) {
              return sum(l.l1BoundVsGold[k]);
            });
        ratios["relative_frobenius_error_vs_gold"] =
            ratioToFullGauss(links, r, fullGauss, seed, [](const LinkRecord& l, std::size_t k) {
              return l.frobeniusErrorVsGold[k];
            });
      }
    }
  }
  if (gold && !links.empty()) entry["gold_noise_share"] = goldNoiseShare(links, r, fig2);
  if (!ratios.empty()) entry["ratio_to_fullgauss"] = ratios;
  return entry;
}

nlohmann::json classReference(const StudyRun& run, const ClassRun& classRun, bool gold, bool fig2) {
  nlohmann::json reference = {{"name", run.referenceName},
                              {"samples", run.referenceSamples},
                              {"relative_standard_error", standardErrorSummary(classRun.links)}};
  if (fig2 && !classRun.links.empty() && !classRun.links.front().referenceL1StandardError.empty()) {
    reference["l1_standard_error"] =
        boundTable(classRun.links, [](const LinkRecord& l) -> const std::vector<double>& {
          return l.referenceL1StandardError;
        });
  }
  if (gold) {
    reference["relative_error_vs_gold"] = statisticsToJson(summarize(column(
        classRun.links, [](const LinkRecord& l) { return l.referenceRelativeErrorVsGold; })));
    if (fig2) {
      reference["l1_error_bound_vs_gold"] =
          boundTable(classRun.links, [](const LinkRecord& l) -> const std::vector<double>& {
            return l.referenceL1BoundVsGold;
          });
      reference["relative_frobenius_error_vs_gold"] = statisticsToJson(summarize(column(
          classRun.links, [](const LinkRecord& l) { return l.referenceFrobeniusErrorVsGold; })));
    }
  }
  return reference;
}

nlohmann::json classTable(const StudyConfig& config, const StudyRun& run, const ClassRun& classRun,
                          bool gold, bool fig2) {
  // Every bootstrap of the class draws from one seed: each comparison on the same links sees
  // the same resamples (docs/study.md, "Seeds").
  const std::uint64_t seed = bootstrapSeed(config.seed, std::uint64_t(classRun.linkClass));
  nlohmann::json rules = nlohmann::json::array();
  for (std::size_t r = 0; r < run.rules.size(); ++r)
    rules.push_back(ruleEntry(run, r, classRun, gold, fig2, seed));
  return {{"links", classRun.links.size()},
          {"candidates", candidateCounts(classRun)},
          {"reference", classReference(run, classRun, gold, fig2)},
          {"rules", rules},
          {"breakdown", studyBreakdown(classRun, run.rules.size(), gold, fig2, fullGaussIndex(run), seed)},
          {"per_link", perLinkScores(classRun, gold, fig2)}};
}

}  // namespace

nlohmann::json studyTable(const StudyConfig& config, const StudyOptions& options,
                          const StudyRun& run) {
  const bool fig2 = config.figure == StudyFigure::fig2;
  nlohmann::json options_ = studyConfigToJson(config);
  options_["gold_requested"] = options.gold;
  std::vector<LinkRecord> allLinks;
  for (const ClassRun& classRun : run.classes)
    allLinks.insert(allLinks.end(), classRun.links.begin(), classRun.links.end());
  nlohmann::json table = {
      {"schema", kSchema},
      {"figure", fig2 ? "fig2" : "fig1"},
      {"options", options_},
      {"reference",
       {{"name", run.referenceName},
        {"samples", run.referenceSamples},
        {"replicates", config.reference.replicates},
        {"standard_error_method",
         "entrywise sample standard deviation of independent replicates "
         "(reference/stratified_reference.h)"},
        {"relative_standard_error", standardErrorSummary(allLinks)}}},
  };
  if (config.sceneLinks) {
    table["scene_links"] = {{"final_active", run.sceneLinks},
                            {"occluded_not_scored", run.sceneOccludedLinks},
                            {"solver_unoccluded", run.sceneSolverUnoccluded},
                            {"solver_partial", run.sceneSolverPartial}};
  }
  if (options.gold) {
    std::map<std::string, int> methods, outerMethods;
    for (const LinkRecord& link : allLinks) {
      ++methods[link.goldMethod];
      if (!link.goldOuterMethod.empty()) ++outerMethods[link.goldOuterMethod];
    }
    const SummaryStatistics own =
        summarize(column(allLinks, [](const LinkRecord& l) { return l.goldRelativeError; }));
    const SummaryStatistics ownLargest = summarize(
        column(allLinks, [](const LinkRecord& l) { return l.goldMaxRelativeError; }));
    int unconverged = 0;
    for (const LinkRecord& link : allLinks) unconverged += link.goldConverged ? 0 : 1;
    table["gold"] = {{"options", goldOptionsToJson(config.gold)},
                     {"links_by_method", methods},
                     {"exact_links_by_outer_method", outerMethods},
                     {"unconverged_links", unconverged},
                     {"own_relative_error", {{"mean", own.mean}, {"max", own.max}}},
                     {"own_max_error_over_largest_entry",
                      {{"mean", ownLargest.mean}, {"max", ownLargest.max}}}};
  }
  if (!fig2) {
    // Figure 1: one class (partial), flattened to the top level.
    const nlohmann::json only = classTable(config, run, run.classes.front(), options.gold, false);
    table["links"] = only["links"];
    table["candidates"] = only["candidates"];
    table["rules"] = only["rules"];
    table["breakdown"] = only["breakdown"];
    table["per_link"] = only["per_link"];
    if (options.gold)
      table["reference"]["relative_error_vs_gold"] = only["reference"]["relative_error_vs_gold"];
  } else {
    nlohmann::json classes = nlohmann::json::object();
    for (const ClassRun& classRun : run.classes) {
      classes[studyClassName(classRun.linkClass)] = classTable(config, run, classRun, options.gold, true);
    }
    table["classes"] = classes;
  }
  if (options.gold) {
    // The worst share of the gold's own error in a rule's mean error, over classes, rules and
    // metrics: the check that no bar of the figure is the gold's noise.
    nlohmann::json worst = {{"share", 0.0}};
    const auto scan = [&](const std::string& className, const nlohmann::json& rules) {
      for (const nlohmann::json& rule : rules) {
        if (!rule.contains("gold_noise_share")) continue;
        for (const auto& [metric, value] : rule["gold_noise_share"].items()) {
          if (worst["share"].is_null()) return;
          if (value.is_null() || value.get<double>() > worst["share"].get<double>()) {
            worst = {{"share", value}, {"class", className}, {"rule", rule["name"]},
                     {"metric", metric}};
          }
        }
      }
    };
    if (!fig2) {
      scan("partial", table["rules"]);
    } else {
      for (const auto& [className, classTableJson] : table["classes"].items()) {
        scan(className, classTableJson["rules"]);
      }
    }
    table["gold"]["noise_check"] = {
        {"limit", kGoldNoiseLimit},
        {"holds", !worst["share"].is_null() && worst["share"].get<double>() <= kGoldNoiseLimit},
        {"worst", worst}};
  }
  return table;
}

}  // namespace radquad
