// `radquad rules [--json]`: lists the registered rules.
#include <iomanip>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>

#include "experiments/commands/commands.h"
#include "quadrature/registry.h"

namespace radquad {
namespace {

void runRules(bool asJson) {
  const auto rules = namedRules();
  if (asJson) {
    nlohmann::json out = nlohmann::json::array();
    for (const auto& rule : rules) {
      const auto degree = rule->degree();
      out.push_back({{"name", rule->name()},
                     {"samples", rule->sampleCount()},
                     {"degree", degree ? nlohmann::json(*degree) : nlohmann::json(nullptr)},
                     {"family", rule->family()},
                     {"citation", rule->citation()}});
    }
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

void addRulesCommand(CLI::App& app) {
  auto asJson = std::make_shared<bool>(false);
  CLI::App* command = app.add_subcommand("rules", "List the registered quadrature rules");
  command->add_flag("--json", *asJson,
                    "Print a JSON array of {name, samples, degree, family, citation}");
  command->callback([asJson] { runRules(*asJson); });
}

}  // namespace radquad
