// Where each rule wins, for the study table (experiments/study/study_breakdown.h).
#include "experiments/study/study_breakdown.h"

#include <map>
#include <string>
#include <vector>

#include "experiments/study/study_metrics.h"
#include "experiments/study/study_statistics.h"

namespace radquad {
namespace {

// Every rule's paired ratio of means to FullGauss's on the same links, with its 95% bootstrap
// interval: [ratio, low, high] per rule (study_statistics.h, pairedRatio).
nlohmann::json ratiosTo(const std::vector<std::vector<double>>& values, std::size_t base,
                        std::uint64_t seed) {
  nlohmann::json out = nlohmann::json::array();
  for (const std::vector<double>& rule : values) {
    const PairedRatio ratio = pairedRatio(rule, values[base], seed);
    out.push_back({ratio.ratio, ratio.low, ratio.high});
  }
  return out;
}

// Mean and median of every rule's relative error (and L1 bound total, Figure 2) over the
// links of one group, rules in the order of "rules".
nlohmann::json groupScores(const std::vector<const LinkRecord*>& group, std::size_t rules,
                           bool gold, bool fig2, int fullGauss, std::uint64_t seed) {
  nlohmann::json out = {{"links", group.size()}};
  if (group.empty()) return out;
  auto scores = [&](const auto& pick) {
    std::vector<double> means, medians, p90s, maxima, shares;
    std::vector<std::vector<double>> values(rules);
    for (std::size_t r = 0; r < rules; ++r) {
      for (const LinkRecord* link : group) values[r].push_back(pick(*link, r));
      const SummaryStatistics statistics = summarize(values[r]);
      means.push_back(statistics.mean);
      medians.push_back(statistics.median);
      p90s.push_back(statistics.p90);
      maxima.push_back(statistics.max);
      shares.push_back(statistics.largestShare);
    }
    nlohmann::json table = {{"mean", means}, {"median", medians}, {"p90", p90s}, {"max", maxima},
                            {"largest_share", shares}};
    if (fullGauss >= 0) table["ratio_to_fullgauss"] = ratiosTo(values, std::size_t(fullGauss), seed);
    return table;
  };
  out["relative_error"] = scores([](const LinkRecord& l, std::size_t r) { return l.relativeError[r]; });
  if (fig2) {
    out["l1_error_bound_total"] =
        scores([](const LinkRecord& l, std::size_t r) { return sum(l.l1Bound[r]); });
    out["relative_frobenius_error"] =
        scores([](const LinkRecord& l, std::size_t r) { return l.frobeniusError[r]; });
  }
  if (gold) {
    out["relative_error_vs_gold"] =
        scores([](const LinkRecord& l, std::size_t r) { return l.relativeErrorVsGold[r]; });
    if (fig2) {
      out["l1_error_bound_total_vs_gold"] =
          scores([](const LinkRecord& l, std::size_t r) { return sum(l.l1BoundVsGold[r]); });
      out["relative_frobenius_error_vs_gold"] =
          scores([](const LinkRecord& l, std::size_t r) { return l.frobeniusErrorVsGold[r]; });
    }
  }
  return out;
}

}  // namespace


nlohmann::json studyBreakdown(const ClassRun& classRun, std::size_t rules, bool gold, bool fig2,
                         int fullGauss, std::uint64_t seed) {
  std::map<std::string, std::vector<const LinkRecord*>> byOccluder;
  for (const LinkRecord& link : classRun.links) {
    // Scene-derived links: by their scene.
    const std::string kind = link.scene.empty() ? occluderKindName(link.occluderKind)
                                                : std::string("scene ") + link.scene;
    byOccluder[kind].push_back(&link);
  }
  nlohmann::json occluders = nlohmann::json::object();
  for (const auto& [kind, group] : byOccluder) {
    occluders[kind] = groupScores(group, rules, gold, fig2, fullGauss, seed);
  }
  constexpr double kBands[] = {0.0, 0.5, 1.0, 2.0, 1e300};
  nlohmann::json distances = nlohmann::json::array();
  for (int band = 0; band < 4; ++band) {
    std::vector<const LinkRecord*> group;
    for (const LinkRecord& link : classRun.links) {
      if (link.distanceFactor >= kBands[band] && link.distanceFactor < kBands[band + 1]) {
        group.push_back(&link);
      }
    }
    nlohmann::json entry = groupScores(group, rules, gold, fig2, fullGauss, seed);
    entry["distance_factor"] = {kBands[band], band == 3 ? nlohmann::json(nullptr)
                                                        : nlohmann::json(kBands[band + 1])};
    distances.push_back(std::move(entry));
  }
  return {{"by_occluder", occluders}, {"by_distance", distances}};
}

}  // namespace radquad
