// `radquad figures [--quick] [--no-gold]`: regenerates Figures 1 and 2: runs the study configs
// experiments/configs/fig1.json and fig2.json (synthetic links) and fig1-scene.json,
// fig2-scene.json (the links of solves of the built-in scenes) (the -quick variants with
// --quick) into results/<name>.json, and draws plots/<name>.{png,svg} with
// plots/figures.py, each table's while the next suite runs. Quick runs go to results/quick/ and
// plots/quick/ so they never overwrite the canonical tables. The report's claims, checked on the
// scene-derived tables, go to results/claims.json (experiments/study/claims.h).
#include <tbb/global_control.h>

#include <algorithm>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "experiments/atomic_file.h"
#include "experiments/commands/commands.h"
#include "experiments/commands/study_override_options.h"
#include "experiments/study/claims.h"
#include "experiments/study/study_output.h"
#include "kernel/input_error.h"

namespace radquad {
namespace {

struct FiguresOptions {
  bool quick = false;
  bool gold = true;
  bool quiet = false;
  std::string resultsDir;
  std::string plotsDir;
  std::string python = "/usr/bin/python3";
  StudyOverrideOptions overrides;
};

void runFigures(const FiguresOptions& options) {
  const std::filesystem::path root = dataRoot();
  const std::string suffix = options.quick ? "-quick" : "";
  // Outputs default to the current folder's results/ and plots/.
  const std::filesystem::path results = !options.resultsDir.empty()
                                            ? std::filesystem::path(options.resultsDir)
                                            : std::filesystem::path(options.quick ? "results/quick" : "results");
  const std::filesystem::path plots = !options.plotsDir.empty()
                                          ? std::filesystem::path(options.plotsDir)
                                          : std::filesystem::path(options.quick ? "plots/quick" : "plots");
  const StudyOverrides overrides = options.overrides.overrides();
  // The scene-derived suites first: their solves leave part of the machine idle, which the
  // plotting of the table before takes up; the last suite's plots are the cheapest.
  const char* figures[] = {"fig1-scene", "fig2-scene", "fig2", "fig1"};
  // Every config is read, and every overriding rule looked up, before the first study runs.
  std::vector<std::filesystem::path> configPaths;
  std::vector<StudyConfig> configs;
  for (const char* figure : figures) {
    configPaths.push_back(root / "experiments/configs" / (std::string(figure) + suffix + ".json"));
    configs.push_back(readStudyConfigWith(configPaths.back(), overrides));
  }
  checkPlotInterpreter(options.python, "--python");
  createOutputDirectory(results);
  createOutputDirectory(plots);
  for (const char* name : {"fig1.json", "fig2.json", "fig1-scene.json", "fig2-scene.json",
                           "claims.json"}) {
    checkOutputPath(results / name, "--results", {});
  }
  std::optional<tbb::global_control> threadLimit;
  options.overrides.limitThreads(threadLimit);
  StudyOptions study;
  study.gold = options.gold;
  study.progress = !options.quiet;
  // Each table is plotted in the background while the next suite runs.
  BackgroundPlots plotting(options.python, "figures.py", results, plots, "figures", options.quiet);
  std::vector<nlohmann::json> tables;
  for (std::size_t k = 0; k < configs.size(); ++k) {
    tables.push_back(runStudyToFile(configs[k], configPaths[k],
                                    results / (std::string(figures[k]) + ".json"), study));
    plotting.start(figures[k]);
  }
  // The report's claims on the scene-derived suites (experiments/study/claims.h), when the
  // rules they compare were scored; otherwise an earlier claims.json would describe other
  // tables, and is removed.
  std::string missing;
  for (const char* rule : kClaimRules) {
    if (!overrides.rules.empty() &&
        std::find(overrides.rules.begin(), overrides.rules.end(), rule) == overrides.rules.end()) {
      missing += std::string(missing.empty() ? "" : ", ") + rule;
    }
  }
  if (!missing.empty()) {
    std::filesystem::remove(results / "claims.json");
    if (!options.quiet) {
      std::cerr << "radquad figures: the report's claims not checked (not scored: " << missing
                << ")\n";
    }
  } else {
    const nlohmann::json claims = reportClaims(tables[0], tables[1], options.gold);  // -scene
    writeFileAtomically(results / "claims.json", claims.dump(2) + "\n");
    if (!options.quiet) {
      std::cerr << "radquad figures: the report's claims on the scene-derived suites:";
      const char* separator = " ";
      for (const char* name : {"fig1_stratified_best", "fig2_gauss_best", "fig2_partial_more_error"}) {
        const nlohmann::json& claim = claims[name];
        std::cerr << separator << name << " " << claim["verdict"].get<std::string>()
                  << (claim["fragile"].get<bool>() ? " (fragile)" : "");
        separator = ", ";
      }
      std::cerr << "\n";
    }
  }
  plotting.finish();
  // Every table and plot is written; a table whose golds fell short fails the run (status 3).
  for (std::size_t k = 0; k < tables.size(); ++k) {
    if (const int unconverged = unconvergedGolds(tables[k]); unconverged > 0) {
      throw unconvergedGoldError(results / (std::string(figures[k]) + ".json"), unconverged);
    }
  }
}

}  // namespace

void addFiguresCommand(CLI::App& app) {
  auto options = std::make_shared<FiguresOptions>();
  CLI::App* command = app.add_subcommand(
      "figures",
      "Regenerate Figures 1 and 2 (synthetic and scene-derived links): results/fig{1,2}{,-scene}.json "
      "and plots/fig{1,2}{,-scene}.{png,svg}");
  command->add_flag("--quick", options->quick,
                    "The small CI suites, into results/quick/ and plots/quick/");
  command->add_flag("--gold,!--no-gold", options->gold,
                    "Score against the gold reference (the default; --no-gold: against the "
                    "paper's reference only, faster)");
  command->add_flag("--quiet", options->quiet, "No progress lines on stderr");
  command->add_option("--results", options->resultsDir,
                      "Directory of the JSON tables (default: results/, or results/quick/, in the current directory)");
  command->add_option("--plots", options->plotsDir,
                      "Directory of the figures (default: plots/, or plots/quick/, in the current directory)");
  command->add_option("--python", options->python, "Python with matplotlib")->capture_default_str();
  options->overrides.addTo(command, "every config's");
  command->callback([options] { runFigures(*options); });
}

}  // namespace radquad
