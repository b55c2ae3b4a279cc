// `radquad baseline TABLE.json --out BASELINE.json [--rules A,B]` and `radquad check
// TABLE.json --baseline BASELINE.json [--junit FILE.xml]`: regression bands of a study suite
// and the check of a table against them (experiments/study/baseline.h; docs/cli.md,
// "Regression bounds"). check exits 0 when every bound holds, 1 when one does not (each
// failure named on stdout: rule, class, metric, value and band), 2 on bad input (a table of
// another suite included).
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "experiments/atomic_file.h"
#include "experiments/commands/commands.h"
#include "experiments/json_input.h"
#include "experiments/study/baseline.h"

namespace radquad {

void addBaselineCommand(CLI::App& app) {
  struct Options {
    std::string table, out;
    std::vector<std::string> rules;
  };
  auto options = std::make_shared<Options>();
  CLI::App* command = app.add_subcommand(
      "baseline", "Write the regression bands of a study table's rules (radquad check reads them)");
  command->add_option("table", options->table, "TABLE.json, as radquad study writes it")->required();
  command->add_option("--out", options->out,
                      "BASELINE.json (atomically); with --rules and an existing file, only "
                      "those rules' bands are replaced")
      ->required();
  command->add_option("--rules", options->rules, "Only these rules (comma-separated)")
      ->delimiter(',');
  command->callback([options] {
    checkOutputPath(options->out, "--out", {options->table});
    const nlohmann::json table = readJsonFile(options->table);
    std::optional<nlohmann::json> existing;
    if (!options->rules.empty() && std::filesystem::exists(options->out)) {
      existing = readJsonFile(options->out);
    }
    const nlohmann::json baseline = makeBaseline(table, options->table, options->rules,
                                                 existing ? &*existing : nullptr);
    writeFileAtomically(options->out, baseline.dump(2) + "\n");
  });
}

void addCheckCommand(CLI::App& app) {
  struct Options {
    std::string table, baseline, junit;
  };
  auto options = std::make_shared<Options>();
  CLI::App* command = app.add_subcommand(
      "check",
      "Check a study table against a baseline's bands: exit 0 when all hold, 1 when one does not");
  command->add_option("table", options->table, "TABLE.json, as radquad study writes it")->required();
  command->add_option("--baseline", options->baseline, "BASELINE.json (radquad baseline)")
      ->required();
  command->add_option("--junit", options->junit, "Also write the checks as JUnit XML (atomically)");
  command->callback([options] {
    if (!options->junit.empty()) {
      checkOutputPath(options->junit, "--junit", {options->table, options->baseline});
    }
    const nlohmann::json table = readJsonFile(options->table);
    const nlohmann::json baseline = readJsonFile(options->baseline);
    const CheckReport report = checkTable(table, options->table, baseline, options->baseline);
    std::cout << report.summary();
    if (!options->junit.empty()) {
      writeFileAtomically(options->junit,
                          junitXml(report, std::filesystem::path(options->table).stem().string()));
    }
    if (!report.holds()) throw CommandFailure("check: bounds do not hold", 1);
  });
}

}  // namespace radquad
