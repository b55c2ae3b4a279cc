// The study's per-link outputs (experiments/study/study_link_tables.h).
#include "experiments/study/study_link_tables.h"

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "experiments/json_input.h"
#include "experiments/study/study_metrics.h"

namespace radquad {
namespace {

// Four significant digits: per-link values are for reading and plotting, not for rescoring.
double rounded(double value) {
  if (value == 0.0 || !std::isfinite(value)) return value;
  const double scale = std::pow(10.0, 3 - std::floor(std::log10(std::fabs(value))));
  return std::round(value * scale) / scale;
}

}  // namespace

nlohmann::json perLinkScores(const ClassRun& classRun, bool gold, bool fig2) {
  nlohmann::json links = nlohmann::json::array();
  for (const LinkRecord& link : classRun.links) {
    nlohmann::json entry = {{"candidate", link.candidate},
                            {"occluder", occluderKindName(link.occluderKind)},
                            {"orientation", orientationName(link.orientation)},
                            {"distance_factor", rounded(link.distanceFactor)},
                            {"visible_fraction", rounded(link.visibleFraction)}};
    if (!link.scene.empty()) entry["scene"] = link.scene;
    auto roundedAll = [](const std::vector<double>& values) {
      std::vector<double> out;
      for (const double value : values) out.push_back(rounded(value));
      return out;
    };
    entry["relative_error"] = roundedAll(link.relativeError);
    if (fig2) {
      std::vector<double> totals;
      for (const auto& bound : link.l1Bound) totals.push_back(sum(bound));
      entry["l1_error_bound_total"] = roundedAll(totals);
      entry["relative_frobenius_error"] = roundedAll(link.frobeniusError);
    }
    if (gold) {
      entry["gold_method"] = link.goldMethod;
      entry["gold_converged"] = link.goldConverged;
      entry["gold_max_error_over_largest_entry"] = rounded(link.goldMaxRelativeError);
      entry["relative_error_vs_gold"] = roundedAll(link.relativeErrorVsGold);
      entry["reference_relative_error_vs_gold"] = rounded(link.referenceRelativeErrorVsGold);
      if (fig2) {
        std::vector<double> totals;
        for (const auto& bound : link.l1BoundVsGold) totals.push_back(sum(bound));
        entry["l1_error_bound_total_vs_gold"] = roundedAll(totals);
        entry["relative_frobenius_error_vs_gold"] = roundedAll(link.frobeniusErrorVsGold);
      }
    }
    links.push_back(std::move(entry));
  }
  return links;
}

std::string linkTableLines(const StudyConfig& config, const StudyRun& run) {
  std::string out;
  for (const ClassRun& classRun : run.classes) {
    for (const LinkRecord& link : classRun.links) {
      if (!link.detail) throw std::logic_error("linkTableLines: the run kept no link details");
      const LinkDetail& detail = *link.detail;
      nlohmann::json occluders = nlohmann::json::array();
      for (const auto& polygon : detail.occluders) occluders.push_back(occluderToJson(polygon));
      nlohmann::json rules = nlohmann::json::array();
      for (std::size_t r = 0; r < run.rules.size(); ++r) {
        nlohmann::json rule = {{"name", run.rules[r].name},
                               {"trials", run.rules[r].trials},
                               {"coupling", matrixToJson(detail.ruleMean[r])}};
        if (run.rules[r].random) {
          rule["standard_deviation"] = matrixToJson(detail.ruleDeviation[r]);
        }
        rules.push_back(std::move(rule));
      }
      nlohmann::json line = {{"class", studyClassName(classRun.linkClass)},
                             {"candidate", link.candidate},
                             {"degree", config.degree()},
                             {"occluder", occluderKindName(link.occluderKind)},
                             {"orientation", orientationName(link.orientation)},
                             {"distance_factor", link.distanceFactor},
                             {"visible_fraction", link.visibleFraction},
                             {"scene", link.scene.empty() ? nlohmann::json(nullptr)
                                                          : nlohmann::json(link.scene)},
                             {"receiver", patchToJson(detail.receiver)},
                             {"source", patchToJson(detail.source)},
                             {"occluders", std::move(occluders)},
                             {"reference",
                              {{"name", run.referenceName},
                               {"coupling", matrixToJson(detail.reference)},
                               {"standard_error", matrixToJson(detail.referenceStandardError)}}},
                             {"rules", std::move(rules)}};
      if (detail.gold.size() > 0) {
        line["gold"] = {{"method", link.goldMethod},
                        {"converged", link.goldConverged},
                        {"coupling", matrixToJson(detail.gold)},
                        {"error", matrixToJson(detail.goldError)}};
      }
      out += line.dump() + "\n";
    }
  }
  return out;
}

}  // namespace radquad
