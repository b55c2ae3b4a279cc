#include "experiments/link_reports.h"

#include <algorithm>
#include <cmath>

#include "experiments/rule_file.h"
#include "experiments/study/study_metrics.h"
#include "experiments/trace_report.h"
#include "kernel/input_error.h"
#include "kernel/patch_intersection.h"
#include "quadrature/estimate.h"
#include "quadrature/prepared_rule.h"
#include "reference/stratified_reference.h"

namespace radquad {
namespace {

// Mean and sample standard deviation (denominator T-1) of T trials, entry by entry, with the
// study's accumulator (Welford's update); `first` receives trial 0 (seed S), the link's
// reported coupling.
nlohmann::json trialStatistics(const PreparedRule& prepared, const Link& link,
                               const LinkReportOptions& options, LinkIntegral& first) {
  CouplingAccumulator accumulator;
  LinkIntegral integral;
  EntrywiseMoments coupling, formFactor;
  for (int trial = 0; trial < options.trials; ++trial) {
    prepared.integrate(link, options.seed + std::uint64_t(trial), accumulator, integral,
                       std::size_t(trial));
    if (trial == 0) first = integral;
    coupling.add(integral.coupling);
    formFactor.add(integral.formFactor);
  }
  return {{"trials", options.trials},
          {"seeds", {options.seed, options.seed + std::uint64_t(options.trials) - 1}},
          {"mean_form_factor", formFactor.mean()(0, 0)},
          {"mean_coupling", matrixToJson(coupling.mean())},
          {"standard_deviation",
           {{"form_factor", formFactor.sampleDeviation()(0, 0)},
            {"coupling", matrixToJson(coupling.sampleDeviation())}}}};
}

const char* goldErrorKind(const std::string& method) {
  if (method == "gauss product") return "difference of the last two Gauss orders";
  if (method == "exact visibility") return "estimated absolute error of the adaptive cubature";
  return "standard error of the mean";
}

}  // namespace

nlohmann::json goldToJson(const GoldReference& gold, const GoldOptions& options) {
  nlohmann::json out = {
      {"method", gold.method},
      {"form_factor", gold.formFactor},
      {"coupling", matrixToJson(gold.coupling)},
      {"error",
       {{"kind", goldErrorKind(gold.method)},
        {"form_factor", gold.formFactorError},
        {"coupling", matrixToJson(gold.couplingError)}}},
      {"converged", gold.converged},
      {"kernel_evaluations", gold.kernelEvaluations},
  };
  if (gold.method == "gauss product") {
    out["gauss_points"] = gold.gaussPoints;
    out["tolerance"] = options.tolerance;
  }
  if (gold.method == "exact visibility") {
    out["tolerance"] = options.exactTolerance;
    out["receiver_points"] = gold.receiverPoints;
    out["shaft_occluders"] = gold.shaftOccluders;
    out["outer_method"] = gold.outerMethod;
    out["critical_segments"] = gold.criticalSegments;
    out["unoccluded_apart"] = gold.unoccludedApart;
    out["confirmed"] = gold.confirmed;
  }
  if (gold.lambert) {
    const LambertCheck& check = *gold.lambert;
    nlohmann::json column = nlohmann::json::array();
    for (Eigen::Index a = 0; a < check.column.size(); ++a) column.push_back(check.column[a]);
    out["lambert_check"] = {{"source_function", 0},
                            {"coupling_column", column},
                            {"max_abs_difference_from_gold", check.maxDifference},
                            {"outer_gauss_points", check.outerPoints},
                            {"outer_error", check.error},
                            {"converged", check.converged}};
  }
  return out;
}

namespace {

// A link's warnings (near-singular: `nearness` is nearnessRatio of its patches; form factor
// outside [0, 1]); `what` names the estimate.
nlohmann::json linkWarnings(double nearness, double formFactor, const std::string& what) {
  nlohmann::json warnings = nlohmann::json::array();
  if (nearness < kNearSingularRatio) {
    warnings.push_back("near-singular link: the patches are " + std::to_string(nearness) +
                       " of the smaller patch's shorter side apart (below " +
                       std::to_string(kNearSingularRatio) +
                       "); product rules converge slowly here and random rules' standard "
                       "errors understate their error");
  }
  if (formFactor > 1.0 + 1e-9 || formFactor < -1e-9) {
    warnings.push_back("form factor " + std::to_string(formFactor) + " outside [0, 1]: " + what +
                       " does not resolve this link");
  }
  return warnings;
}

// `warnings` into the report (when there are any) and onto `log`.
void addWarnings(nlohmann::json& out, const nlohmann::json& warnings, std::ostream* log) {
  if (warnings.empty()) return;
  out["warnings"] = warnings;
  if (log == nullptr) return;
  for (const auto& warning : warnings) {
    *log << "radquad: warning: " << warning.get<std::string>() << "\n";
  }
}

}  // namespace

nlohmann::json linkReport(const LinkGeometry& description,
                          const std::shared_ptr<const Rule>& rule,
                          const LinkReportOptions& options, const std::string& where,
                          std::ostream* log) {
  if (options.trials > 1 && options.seed > ~std::uint64_t(0) - std::uint64_t(options.trials - 1)) {
    throw InputError("seed " + std::to_string(options.seed) + " with " +
                     std::to_string(options.trials) + " trials: the last seed would pass 2^64 - 1");
  }
  checkSampleBudget(*rule, rule->isRandom() ? options.trials : 1, "rule " + rule->name());
  checkDrawCount(*rule, options.trials, "trials");
  const PreparedRule prepared(rule, options.degree);
  const BuiltLink sceneLink = description.build();
  // Trials of a random rule: trial 0 (seed S) is the reported coupling, integrated once.
  const bool trials = options.trials > 1 && prepared.rule().isRandom();
  LinkIntegral integral;
  nlohmann::json statistics;
  if (trials) {
    statistics = trialStatistics(prepared, sceneLink.link, options, integral);
  } else {
    integral = prepared.integrate(sceneLink.link, options.seed);
  }
  if (!integral.coupling.allFinite() || !std::isfinite(integral.formFactor)) {
    throw ComputationError(where + ": rule " + prepared.rule().name() +
                           " gave a non-finite coupling");
  }
  const auto declared = prepared.rule().degree();
  nlohmann::json out = {
      {"rule", prepared.rule().name()},
      {"samples", prepared.rule().sampleCount()},
      {"rule_degree", declared ? nlohmann::json(*declared) : nlohmann::json(nullptr)},
      {"degree", options.degree},
      {"seed", options.seed},
      {"kernel_evaluations", integral.kernelEvaluations},
      {"form_factor", integral.formFactor},
      {"coupling", matrixToJson(integral.coupling)},
      {"visible_fraction", integral.visibleFraction()},
      {"rays_cast", integral.raysCast},
  };
  // Near-singular links and form factors outside [0, 1] are flagged, never printed as fine.
  nlohmann::json warnings = linkWarnings(
      nearnessRatio(description.receiver, description.source), integral.formFactor, "the rule");
  addWarnings(out, warnings, log);
  if (options.trials > 1) {
    if (trials) {
      out.update(statistics);
    } else {
      if (log != nullptr) {
        *log << "radquad: warning: rule " << prepared.rule().name()
             << " is deterministic; --trials " << options.trials << " ignored\n";
      }
      out["trials"] = 1;
    }
  }
  return out;
}

nlohmann::json referenceReport(const LinkGeometry& description,
                               const ReferenceReportOptions& options, const std::string& link,
                               std::ostream* log) {
  const BuiltLink sceneLink = description.build();
  ReferenceOptions referenceOptions;
  referenceOptions.replicates = options.replicates;
  const ReferenceEstimate estimate =
      stratifiedReference(sceneLink.link, options.degree, options.seed, referenceOptions);
  nlohmann::json out = {
      {"link", link},
      {"rule", "Reference"},
      {"samples", estimate.integral.kernelEvaluations},
      {"degree", options.degree},
      {"seed", options.seed},
      {"replicates", estimate.replicates},
      {"form_factor", estimate.integral.formFactor},
      {"coupling", matrixToJson(estimate.integral.coupling)},
      {"standard_error",
       {{"method", "sample standard deviation of independent replicates"},
        {"form_factor", estimate.formFactorStandardError},
        {"coupling", matrixToJson(estimate.couplingStandardError)}}},
      {"kernel_evaluations", estimate.totalKernelEvaluations},
      {"visible_fraction", estimate.integral.visibleFraction()},
  };
  if (options.gold) {
    const GoldReference gold =
        goldReference(sceneLink.link, options.degree, options.seed, options.goldOptions);
    out["gold"] = goldToJson(gold, options.goldOptions);
    const double difference = estimate.integral.formFactor - gold.formFactor;
    out["reference_minus_gold"] = {
        {"form_factor", difference},
        {"max_abs_coupling", (estimate.integral.coupling - gold.coupling).cwiseAbs().maxCoeff()},
        {"form_factor_in_standard_errors", estimate.formFactorStandardError > 0.0
                                               ? difference / estimate.formFactorStandardError
                                               : 0.0}};
  }
  // The replicates' spread estimates the error only where the kernel's variance is bounded:
  // on a near-singular link it is not, and the standard error is flagged as unreliable.
  const double nearness = nearnessRatio(description.receiver, description.source);
  nlohmann::json warnings = linkWarnings(nearness, estimate.integral.formFactor, "the reference");
  out["standard_error"]["reliable"] = nearness >= kNearSingularRatio;
  if (options.gold) {
    const double inErrors = out["reference_minus_gold"]["form_factor_in_standard_errors"];
    if (std::abs(inErrors) > 5.0) {
      warnings.push_back("the reference is " + std::to_string(inErrors) +
                         " standard errors from the gold: its standard error understates its "
                         "error on this link");
    }
  }
  addWarnings(out, warnings, log);
  return out;
}

}  // namespace radquad
