// `radquad link LINK.json --rule NAME [--degree D] [--seed S] [--trials T]`: integrates one
// link with one rule and prints the coupling as one JSON object on stdout. With --trials T a
// random rule runs T times with seeds S, S+1, ..., S+T-1 and the output adds the mean
// coupling and form factor, the per-coefficient sample standard deviation and T.
#include <iostream>
#include <memory>
#include <string>

#include "experiments/rule_file.h"
#include "experiments/commands/commands.h"
#include "experiments/json_input.h"
#include "experiments/link_reports.h"
#include "experiments/trace_report.h"
#include "kernel/input_error.h"

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

void runLink(LinkOptions options) {
  options.seed = parseDecimalOption(options.seedText, "--seed", 0, ~std::uint64_t(0));
  if (options.trials > 1 && options.seed > ~std::uint64_t(0) - std::uint64_t(options.trials - 1)) {
    throw InputError("--seed " + options.seedText + " with --trials " +
                     std::to_string(options.trials) + ": the last seed would pass 2^64 - 1");
  }
  const LinkGeometry description = readLinkFile(options.linkPath);
  LinkReportOptions report;
  report.degree = options.degree;
  report.seed = options.seed;
  report.trials = options.trials;
  const nlohmann::json out = linkReport(description, findAnyRule(options.ruleName), report,
                                        options.linkPath, &std::cerr);
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
