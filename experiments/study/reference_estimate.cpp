#include "experiments/study/reference_estimate.h"

#include <memory>

#include "experiments/json_input.h"
#include "kernel/input_error.h"
#include "quadrature/random/seeds.h"
#include "quadrature/rules/stratified.h"

namespace radquad {
namespace {

int integerIn(const nlohmann::json& object, const char* key, const std::string& where, int low,
              int high, int fallback) {
  if (!object.contains(key)) return fallback;
  const auto& value = object[key];
  if (!value.is_number_integer() || value.get<long long>() < low || value.get<long long>() > high) {
    throw InputError(where + ": " + key + ": expected an integer in [" + std::to_string(low) +
                     ", " + std::to_string(high) + "]");
  }
  return value.get<int>();
}

}  // namespace

ReferenceEstimator::ReferenceEstimator(const ReferenceOptions& options, int degree)
    : options_(options),
      degree_(degree),
      draw_(std::make_shared<StratifiedRule>(options.strataPerAxis), degree) {}

std::string ReferenceEstimator::name() const {
  return options_.strataPerAxis == 10 ? "Reference" : draw_.rule().name();
}

void ReferenceEstimator::draw(const Link& link, std::uint64_t seed,
                              CouplingAccumulator& accumulator, LinkIntegral& result) const {
  // Replicate 0 of stratifiedReference uses `seed` itself (replicateSeed(seed, 0) == seed).
  draw_.integrate(link, seed, accumulator, result);
}

ReferenceResult ReferenceEstimator::estimate(const Link& link, std::uint64_t seed,
                                             const LinkIntegral& reportedDraw,
                                             CouplingAccumulator& accumulator) const {
  // Welford's running mean and sum of squared deviations, entry by entry (Knuth TAOCP vol. 2,
  // 4.2.2); the sample standard deviation (denominator R - 1) of the R draws estimates the
  // standard deviation of one draw, the reported one's standard error.
  const Eigen::MatrixXd& first = reportedDraw.coupling;
  Eigen::MatrixXd mean = first;
  Eigen::MatrixXd squares = Eigen::MatrixXd::Zero(first.rows(), first.cols());
  LinkIntegral replicate;
  for (int j = 1; j < options_.replicates; ++j) {
    draw_.integrate(link, replicateSeed(seed, std::uint32_t(j)), accumulator, replicate);
    const Eigen::MatrixXd delta = replicate.coupling - mean;
    mean += delta / double(j + 1);
    squares += delta.cwiseProduct(replicate.coupling - mean);
  }
  return {reportedDraw, (squares / double(options_.replicates - 1)).cwiseSqrt()};
}

ReferenceOptions parseReferenceOptions(const nlohmann::json& value, const std::string& where) {
  checkKeys(value, where, {"strata_per_axis", "replicates"}, {});
  ReferenceOptions options;
  options.strataPerAxis = integerIn(value, "strata_per_axis", where, 1, 56, options.strataPerAxis);
  options.replicates = integerIn(value, "replicates", where, 2, 100000, options.replicates);
  return options;
}

nlohmann::json referenceOptionsToJson(const ReferenceOptions& options) {
  return {{"strata_per_axis", options.strataPerAxis}, {"replicates", options.replicates}};
}

GoldOptions studyGoldOptions() {
  GoldOptions options;
  options.exactTolerance = 3e-4;
  options.denseStrata = 16;
  options.denseReplicates = 8;
  return options;
}

GoldOptions parseGoldOptions(const nlohmann::json& value, const std::string& where) {
  checkKeys(value, where,
            {"method", "tolerance", "exact_tolerance", "max_evaluations", "max_exact_occluders",
             "dense_strata", "dense_replicates"},
            {});
  GoldOptions options = studyGoldOptions();
  if (value.contains("method")) {
    if (!value["method"].is_string()) throw InputError(where + ": method must be a string");
    options.method = parseGoldMethod(value["method"].get<std::string>(), where + ": method");
  }
  for (const auto& [key, field] : {std::pair{"tolerance", &options.tolerance},
                                   std::pair{"exact_tolerance", &options.exactTolerance}}) {
    if (!value.contains(key)) continue;
    *field = finiteNumber(value[key], where + ": " + key);
    if (!(*field > 0.0 && *field < 1.0)) {
      throw InputError(where + ": " + key + " must lie in (0, 1)");
    }
  }
  options.maxEvaluations = std::size_t(
      integerIn(value, "max_evaluations", where, 1000, 1000000000, int(options.maxEvaluations)));
  options.maxExactOccluders = std::size_t(integerIn(value, "max_exact_occluders", where, 0,
                                                    1000000, int(options.maxExactOccluders)));
  options.denseStrata = integerIn(value, "dense_strata", where, 1, 56, options.denseStrata);
  options.denseReplicates =
      integerIn(value, "dense_replicates", where, 2, 100000, options.denseReplicates);
  return options;
}

nlohmann::json goldOptionsToJson(const GoldOptions& options) {
  return {{"method", goldMethodName(options.method)},
          {"tolerance", options.tolerance},
          {"exact_tolerance", options.exactTolerance},
          {"max_evaluations", options.maxEvaluations},
          {"max_exact_occluders", options.maxExactOccluders},
          {"dense_strata", options.denseStrata},
          {"dense_replicates", options.denseReplicates}};
}

}  // namespace radquad
