// The error tables of Figures 1 and 2 (field meanings: README.md, "The study").
#include <cmath>
#include <map>

#include "experiments/study/reference_estimate.h"
#include "experiments/study/study_metrics.h"
#include "experiments/study/study_runner.h"

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
  std::vector<double> means, sems;
  for (const auto& values : perFunction) {
    const SummaryStatistics statistics = summarize(values);
    means.push_back(statistics.mean);
    sems.push_back(statistics.sem);
  }
  double total = 0.0;
  for (const double mean : means) total += mean;
  return {{"per_source_function", means},
          {"total", total},
          {"per_source_function_sem", sems},
          {"total_sem", summarize(totals).sem}};
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
                            {"reference_rays", run.referenceRays},
                            {"accepted_by_occluder", byOccluder},
                            {"accepted_by_orientation", byOrientation}};
  if (run.available > 0) counts["scene_links_of_class"] = run.available;
  return counts;
}

nlohmann::json ruleEntry(const StudyRun& run, std::size_t r, const ClassRun& classRun, bool gold,
                         bool fig2) {
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
  if (fig2) {
    entry["l1_error_bound"] = boundTable(
        links, [r](const LinkRecord& l) -> const std::vector<double>& { return l.l1Bound[r]; });
  }
  if (gold) {
    entry["relative_error_vs_gold"] = statisticsToJson(
        summarize(column(links, [r](const LinkRecord& l) { return l.relativeErrorVsGold[r]; })));
    if (fig2) {
      entry["l1_error_bound_vs_gold"] = boundTable(
          links,
          [r](const LinkRecord& l) -> const std::vector<double>& { return l.l1BoundVsGold[r]; });
    }
  }
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
    }
  }
  return reference;
}

nlohmann::json classTable(const StudyRun& run, const ClassRun& classRun, bool gold, bool fig2) {
  nlohmann::json rules = nlohmann::json::array();
  for (std::size_t r = 0; r < run.rules.size(); ++r)
    rules.push_back(ruleEntry(run, r, classRun, gold, fig2));
  return {{"links", classRun.links.size()},
          {"candidates", candidateCounts(classRun)},
          {"reference", classReference(run, classRun, gold, fig2)},
          {"rules", rules}};
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
                            {"occluded_not_scored", run.sceneOccludedLinks}};
  }
  if (options.gold) {
    std::map<std::string, int> methods;
    for (const LinkRecord& link : allLinks) ++methods[link.goldMethod];
    const SummaryStatistics own =
        summarize(column(allLinks, [](const LinkRecord& l) { return l.goldRelativeError; }));
    const SummaryStatistics ownLargest = summarize(
        column(allLinks, [](const LinkRecord& l) { return l.goldMaxRelativeError; }));
    int unconverged = 0;
    for (const LinkRecord& link : allLinks) unconverged += link.goldConverged ? 0 : 1;
    table["gold"] = {{"options", goldOptionsToJson(config.gold)},
                     {"links_by_method", methods},
                     {"unconverged_links", unconverged},
                     {"own_relative_error", {{"mean", own.mean}, {"max", own.max}}},
                     {"own_max_error_over_largest_entry",
                      {{"mean", ownLargest.mean}, {"max", ownLargest.max}}}};
  }
  if (!fig2) {
    // Figure 1: one class (partial), flattened to the top level.
    const nlohmann::json only = classTable(run, run.classes.front(), options.gold, false);
    table["links"] = only["links"];
    table["candidates"] = only["candidates"];
    table["rules"] = only["rules"];
    if (options.gold)
      table["reference"]["relative_error_vs_gold"] = only["reference"]["relative_error_vs_gold"];
  } else {
    nlohmann::json classes = nlohmann::json::object();
    for (const ClassRun& classRun : run.classes) {
      classes[studyClassName(classRun.linkClass)] = classTable(run, classRun, options.gold, true);
    }
    table["classes"] = classes;
  }
  return table;
}

}  // namespace radquad
