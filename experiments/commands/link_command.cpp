// `radquad link LINK.json --rule NAME [--degree D] [--seed S] [--trials T]`: integrates one
// link with one rule and prints the coupling as one JSON object on stdout. With --trials T a
// random rule runs T times with seeds S, S+1, ..., S+T-1 and the output adds the mean
// coupling and form factor, the per-coefficient sample standard deviation and T.
#include <algorithm>
#include <cmath>
#include <iostream>
#include <memory>
#include <string>

#include "experiments/rule_file.h"
#include "experiments/commands/commands.h"
#include "experiments/json_input.h"
#include "experiments/trace_report.h"
#include "kernel/input_error.h"
#include "kernel/patch_intersection.h"
#include "quadrature/prepared_rule.h"
#include "quadrature/registry.h"

namespace radquad {
namespace {

struct LinkOptions {
  std::string linkPath;
  std::string ruleName;
  int degree = 0;
  std::string seedText = "0";
  std::uint64_t seed = 0;
  int trials = 1;
};

// Mean and sample standard deviation (denominator T-1) of T trials, entry by entry.
nlohmann::json trialStatistics(const PreparedRule& prepared, const Link& link,
                               const LinkOptions& options) {
  CouplingAccumulator accumulator;
  LinkIntegral integral;
  Eigen::MatrixXd sum, squares;
  double formFactorSum = 0.0, formFactorSquares = 0.0;
  for (int trial = 0; trial < options.trials; ++trial) {
    prepared.integrate(link, options.seed + std::uint64_t(trial), accumulator, integral);
    if (trial == 0) {
      sum = Eigen::MatrixXd::Zero(integral.coupling.rows(), integral.coupling.cols());
      squares = sum;
    }
    sum += integral.coupling;
    squares += integral.coupling.cwiseAbs2();
    formFactorSum += integral.formFactor;
    formFactorSquares += integral.formFactor * integral.formFactor;
  }
  const double count = options.trials;
  const Eigen::MatrixXd mean = sum / count;
  const double formFactorMean = formFactorSum / count;
  const double denominator = count > 1 ? count - 1.0 : 1.0;
  const Eigen::MatrixXd deviation =
      ((squares - count * mean.cwiseAbs2()) / denominator).cwiseMax(0.0).cwiseSqrt();
  const double formFactorDeviation = std::sqrt(
      std::max(0.0, (formFactorSquares - count * formFactorMean * formFactorMean) / denominator));
  return {{"trials", options.trials},
          {"seeds", {options.seed, options.seed + std::uint64_t(options.trials) - 1}},
          {"mean_form_factor", formFactorMean},
          {"mean_coupling", matrixToJson(mean)},
          {"standard_deviation",
           {{"form_factor", formFactorDeviation}, {"coupling", matrixToJson(deviation)}}}};
}

void runLink(LinkOptions options) {
  options.seed = parseDecimalOption(options.seedText, "--seed", 0, ~std::uint64_t(0));
  if (options.trials > 1 && options.seed > ~std::uint64_t(0) - std::uint64_t(options.trials - 1)) {
    throw InputError("--seed " + options.seedText + " with --trials " +
                     std::to_string(options.trials) + ": the last seed would pass 2^64 - 1");
  }
  const LinkDescription description = readLinkFile(options.linkPath);
  const PreparedRule prepared(findAnyRule(options.ruleName), options.degree);
  const SceneLink sceneLink = buildSceneLink(description);
  const LinkIntegral integral = prepared.integrate(sceneLink.link, options.seed);
  if (!integral.coupling.allFinite() || !std::isfinite(integral.formFactor)) {
    throw ComputationError(options.linkPath + ": rule " + prepared.rule().name() +
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
  nlohmann::json warnings = nlohmann::json::array();
  const double nearness = nearnessRatio(description.receiver, description.source);
  if (nearness < kNearSingularRatio) {
    warnings.push_back("near-singular link: the patches are " + std::to_string(nearness) +
                       " of the smaller patch's shorter side apart (below " +
                       std::to_string(kNearSingularRatio) +
                       "); product rules converge slowly here and random rules' standard "
                       "errors understate their error");
  }
  if (integral.formFactor > 1.0 + 1e-9 || integral.formFactor < -1e-9) {
    warnings.push_back("form factor " + std::to_string(integral.formFactor) +
                       " outside [0, 1]: the rule does not resolve this link");
  }
  if (!warnings.empty()) {
    out["warnings"] = warnings;
    for (const auto& warning : warnings) {
      std::cerr << "radquad: warning: " << warning.get<std::string>() << "\n";
    }
  }
  if (options.trials > 1) {
    if (prepared.rule().isRandom()) {
      out.update(trialStatistics(prepared, sceneLink.link, options));
    } else {
      std::cerr << "radquad: warning: rule " << prepared.rule().name()
                << " is deterministic; --trials " << options.trials << " ignored\n";
      out["trials"] = 1;
    }
  }
  std::cout << out.dump(2) << "\n";
}

}  // namespace

void addLinkCommand(CLI::App& app) {
  auto options = std::make_shared<LinkOptions>();
  CLI::App* command = app.add_subcommand(
      "link", "Integrate the coupling of one link with one rule; prints JSON on stdout");
  command
      ->add_option("link", options->linkPath,
                   "LINK.json: {\"receiver\": PATCH, \"source\": PATCH, \"occluders\": [PATCH...]}")
      ->required();
  command->add_option("--rule", options->ruleName, "Rule name (see `radquad rules`)")->required();
  command
      ->add_option("--degree", options->degree,
                   "Basis degree d, 0..8 ((d+1)^2 functions per patch)")
      ->capture_default_str();
  command->add_option("--seed", options->seedText, "Seed of random rules, a decimal 0..2^64-1")
      ->capture_default_str();
  command
      ->add_option("--trials", options->trials,
                   "Random rules: run T trials with seeds S..S+T-1 and report mean and "
                   "standard deviation (1..100000, the study's cap)")
      ->check(CLI::Range(1, 100000))
      ->capture_default_str();
  command->callback([options] { runLink(*options); });
}

}  // namespace radquad
