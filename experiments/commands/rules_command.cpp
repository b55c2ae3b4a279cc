// `radquad rules [--json]`: lists the registered rules; `radquad rules --dump NAME [--seed S]
// [--draws T]` prints one rule's points in the rule-file format (experiments/rule_file.h): a
// random rule's draw for S, or its T draws for seeds S..S+T-1 as a rule of listed draws.
#include <iomanip>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>

#include "experiments/commands/commands.h"
#include "experiments/json_input.h"
#include "experiments/rule_file.h"
#include "experiments/trace_report.h"
#include "quadrature/registry.h"

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

}  // namespace

struct RulesOptions {
  bool asJson = false;
  std::string dump;
  std::string seedText = "0";
  int draws = 0;
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
  command->callback([options] {
    if (options->dump.empty()) {
      runRules(options->asJson);
      return;
    }
    const std::uint64_t seed =
        parseDecimalOption(options->seedText, "--seed", 0, ~std::uint64_t(0));
    std::cout << ruleToJson(*findAnyRule(options->dump), seed, options->draws).dump(1) << "\n";
  });
}

}  // namespace radquad
