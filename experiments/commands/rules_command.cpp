// `radquad rules [--json]`: lists the registered rules; `radquad rules --dump NAME [--seed S]
// [--draws T] [--degree-check]` prints one rule's points in the rule-file format
// (experiments/rule_file.h): a random rule's draw for S, or its T draws for seeds S..S+T-1 as
// a rule of listed draws. --degree-check measures the total degree the written points
// integrate exactly (the registry test's check, on what was written) and exits 1 when it is
// not the declared one.
#include <algorithm>
#include <cstdio>
#include <iomanip>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>

#include "experiments/commands/commands.h"
#include "experiments/json_input.h"
#include "experiments/rule_file.h"
#include "experiments/trace_report.h"
#include "kernel/input_error.h"
#include "quadrature/registry.h"
#include "quadrature/rules/data_rule.h"

namespace radquad {
namespace {

void runRules(bool asJson) {
  const auto rules = namedRules();
  if (asJson) {
    const nlohmann::json out = registeredRulesJson();
    std::cout << out.dump(2) << "\n";
    return;
  }
  std::cout << std::left << std::setw(16) << "name" << std::setw(9) << "samples" << std::setw(8)
            << "degree"
            << "family\n";
  for (const auto& rule : rules) {
    const auto degree = rule->degree();
    std::cout << std::setw(16) << rule->name() << std::setw(9) << rule->sampleCount()
              << std::setw(8) << (degree ? std::to_string(*degree) : std::string("-"))
              << rule->family() << "\n";
  }
  std::cout << "\nparametrised forms:";
  for (const auto& form : parametrisedRuleForms()) std::cout << " " << form;
  std::cout << "\n";
}

// The highest total degree every written draw integrates exactly (exactnessDegree, the data
// rules' check), at most `cap`; `failing` gets the largest error at the degree above (0 when
// capped).
int exactDegree(const Rule& rule, std::uint64_t seed, int draws, int cap, double& failing) {
  int exact = cap;
  failing = 0.0;
  auto lower = [&](const RuleSamples& set) {
    double error = 0.0;
    const int degree = exactnessDegree(flattenedPoints(set), exact, error);
    if (degree < exact) {
      exact = degree;
      failing = error;
    }
  };
  if (rule.drawCount() > 0) {
    for (std::size_t d = 0; d < rule.drawCount(); ++d) lower(rule.listedDraw(d));
  } else {
    for (int d = 0; d < std::max(draws, 1); ++d) lower(rule.samples(seed + std::uint64_t(d)));
  }
  return exact;
}

// Reports on stderr; CommandFailure (exit 1) when the measured degree is not the declared one
// (a random rule declares none: its measured degree is reported only).
void checkDegree(const Rule& rule, std::uint64_t seed, int draws) {
  const auto declared = rule.degree();
  const int cap = kMaxDataRuleDegree;
  double failing = 0.0;
  const int exact = exactDegree(rule, seed, draws, cap, failing);
  std::string text = "rule " + rule.name() + ": exact to degree " + std::to_string(exact);
  if (exact < cap) {
    char error[32];
    std::snprintf(error, sizeof error, "%.3g", failing);
    text += ", not to degree " + std::to_string(exact + 1) + " (largest error " + error + ")";
  } else {
    text += " at least (checked up to " + std::to_string(cap) + ")";
  }
  if (!declared) {
    std::cerr << "radquad rules: " << text << "; no degree declared\n";
    return;
  }
  text += "; declared " + std::to_string(*declared);
  if (exact != *declared) throw CommandFailure("rules: " + text, 1);
  std::cerr << "radquad rules: " << text << "\n";
}

}  // namespace

struct RulesOptions {
  bool asJson = false;
  std::string dump;
  std::string seedText = "0";
  int draws = 0;
  bool degreeCheck = false;
};

void addRulesCommand(CLI::App& app) {
  auto options = std::make_shared<RulesOptions>();
  CLI::App* command = app.add_subcommand("rules", "List the registered quadrature rules");
  command->add_flag("--json", options->asJson,
                    "Print a JSON array of {name, samples, degree, family, citation}");
  command->add_option("--dump", options->dump,
                      "Print one rule's points and weights in the rule-file format (File:PATH "
                      "reads it back); a random rule's draw for --seed");
  command->add_option("--seed", options->seedText, "Seed of a random rule's draw, a decimal 0..2^64-1")
      ->capture_default_str();
  command->add_option("--draws", options->draws,
                      "A random rule's draws for seeds S..S+T-1, written as a rule of listed "
                      "draws (its trial t uses draw t: `radquad link --trials T --seed S` gives "
                      "the same numbers with either)")
      ->check(CLI::Range(1, 100000));
  command->add_flag("--degree-check", options->degreeCheck,
                    "With --dump: measure the total degree the written points integrate "
                    "exactly, report it on stderr, exit 1 when it is not the declared one");
  command->callback([options] {
    if (options->dump.empty()) {
      if (options->degreeCheck) throw InputError("--degree-check: needs --dump NAME");
      runRules(options->asJson);
      return;
    }
    const std::uint64_t seed =
        parseDecimalOption(options->seedText, "--seed", 0, ~std::uint64_t(0));
    const auto rule = findAnyRule(options->dump);
    std::cout << ruleToJson(*rule, seed, options->draws).dump(1) << "\n";
    if (options->degreeCheck) checkDegree(*rule, seed, options->draws);
  });
}

}  // namespace radquad
