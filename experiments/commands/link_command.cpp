// `radquad link LINK.json --rule NAME [--degree D] [--seed S]`: integrates one link with one
// rule and prints the coupling as one JSON object on stdout.
#include <iostream>
#include <memory>
#include <string>

#include "experiments/commands/commands.h"
#include "experiments/json_input.h"
#include "quadrature/prepared_rule.h"
#include "quadrature/registry.h"

namespace radquad {
namespace {

struct LinkOptions {
  std::string linkPath;
  std::string ruleName;
  int degree = 0;
  std::uint64_t seed = 0;
};

void runLink(const LinkOptions& options) {
  const LinkDescription description = readLinkFile(options.linkPath);
  const PreparedRule prepared(findRule(options.ruleName), options.degree);
  const SceneLink sceneLink = buildSceneLink(description);
  const LinkIntegral integral = prepared.integrate(sceneLink.link, options.seed);
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
  command->add_option("--seed", options->seed, "Seed of random rules")->capture_default_str();
  command->callback([options] { runLink(*options); });
}

}  // namespace radquad
