// `radquad adaptive`: the adaptive Gauss rules of Gershbein 1995 (section 5, Figure 4, Plate
// 1) measured in the radiosity solver. For d = 1, 2, 3 on the built-in scenes it solves with
// fixed, adaptive and adaptive-novis rules and tabulates kernel evaluations, their ratios
// beside the theoretical best ((d+1)^2) and the report's observed values, the wall-time
// ratios and the relative L2 differences from the fixed solution; sweeps ErrThres on one
// scene; renders the cubic cornell scene three ways (Plate 1). Writes results/adaptive.json,
// results/plate1/*.png, then plots/adaptive.png and results/plate1.png with plots/adaptive.py.
#include <tbb/global_control.h>

#include <cstdio>
#include <iostream>
#include <iterator>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "experiments/adaptive/adaptive_runs.h"
#include "experiments/atomic_file.h"
#include "experiments/commands/commands.h"
#include "experiments/solve_report.h"
#include "experiments/study/study_output.h"
#include "kernel/input_error.h"
#include "radiosity/scene.h"

namespace radquad {
namespace {

struct AdaptiveCommandOptions {
  AdaptiveRunOptions runs;
  std::string resultsDir;
  std::string plotsDir;
  std::string python = "/usr/bin/python3";
  int threads = 0;
};

void runAdaptive(const AdaptiveCommandOptions& command) {
  if (!(command.runs.threshold >= 0.0)) throw InputError("--threshold: must be >= 0");
  if (!(command.runs.bfEpsilon > 0.0)) throw InputError("--bf-eps: must be > 0");
  if (!(command.runs.sweepBfEpsilon > 0.0)) throw InputError("--sweep-bf-eps: must be > 0");
  for (double t : command.runs.sweepThresholds) {
    if (!(t >= 0.0)) throw InputError("--sweep: thresholds must be >= 0");
  }
  // Every scene is checked before the first solve (a bad --sweep-scene used to fail only
  // after the table's solves); the parser checks the degrees.
  for (const std::string& scene : command.runs.scenes) {
    if (!builtinScene(scene)) {
      throw InputError("--scenes " + scene + ": not a built-in scene (cornell, slats)");
    }
  }
  if (!builtinScene(command.runs.sweepScene)) {
    throw InputError("--sweep-scene " + command.runs.sweepScene +
                     ": not a built-in scene (cornell, slats)");
  }
  checkPlotInterpreter(command.python, "--python");
  std::optional<tbb::global_control> threadLimit;
  if (command.threads > 0) {
    threadLimit.emplace(tbb::global_control::max_allowed_parallelism, std::size_t(command.threads));
  }
  // Outputs default to the current folder's results/ and plots/.
  const std::filesystem::path results =
      command.resultsDir.empty() ? std::filesystem::path("results")
                                 : std::filesystem::path(command.resultsDir);
  const std::filesystem::path plots =
      command.plotsDir.empty() ? std::filesystem::path("plots") : std::filesystem::path(command.plotsDir);
  createOutputDirectory(results / "plate1");
  createOutputDirectory(plots);

  nlohmann::json out = runAdaptiveExperiments(command.runs, results / "plate1");
  // Times change from run to run: they go to the run record (results/adaptive.run.json).
  std::vector<std::string> timingKeys = {"elapsed_seconds_runs", "coupling_seconds_runs",
                                         "time_ratio", "coupling_time_ratio"};
  timingKeys.insert(timingKeys.end(), std::begin(kSolveTimingKeys), std::end(kSolveTimingKeys));
  const nlohmann::json record = splitRunRecord(out, timingKeys);
  writeFileAtomically(results / "adaptive.json", out.dump(2) + "\n");
  writeRunRecord(results / "adaptive.json", record);
  if (!command.runs.quiet)
    std::cerr << "radquad adaptive: wrote " << (results / "adaptive.json") << "\n";

  runPlotScript(command.python, "adaptive.py", results, plots, "adaptive", command.runs.quiet);
}

}  // namespace

void addAdaptiveCommand(CLI::App& app) {
  auto options = std::make_shared<AdaptiveCommandOptions>();
  CLI::App* command = app.add_subcommand(
      "adaptive",
      "The adaptive Gauss rules against fixed rules: results/adaptive.json, plots/adaptive.png, "
      "results/plate1.png");
  command
      ->add_option(
          "--threshold", options->runs.threshold,
          "ErrThres of the table and the plate (fraction of the scene's emitted radiosity)")
      ->capture_default_str();
  command->add_option("--bf-eps", options->runs.bfEpsilon, "BF threshold of the table")
      ->capture_default_str();
  command->add_option("--sweep", options->runs.sweepThresholds, "ErrThres values of the sweep")
      ->capture_default_str();
  command->add_option("--sweep-scene", options->runs.sweepScene, "Scene of the sweep")
      ->capture_default_str();
  command->add_option("--sweep-degree", options->runs.sweepDegree, "Basis degree of the sweep")
      ->check(CLI::Range(1, 3))
      ->capture_default_str();
  command->add_option("--sweep-bf-eps", options->runs.sweepBfEpsilon, "BF threshold of the sweep")
      ->capture_default_str();
  command->add_option("--degrees", options->runs.degrees, "Basis degrees of the table")
      ->check(CLI::Range(1, 3))
      ->capture_default_str();
  command->add_option("--scenes", options->runs.scenes, "Built-in scenes of the table")
      ->capture_default_str();
  command
      ->add_option("--timing-repeats", options->runs.timingRepeats,
                   "Solves of each table configuration; its times are the fastest")
      ->check(CLI::Range(1, 100))
      ->capture_default_str();
  command->add_option("--results", options->resultsDir,
                      "Directory of the JSON and the plate (default: results/ in the current directory)");
  command->add_option("--plots", options->plotsDir,
                      "Directory of adaptive.png (default: plots/ in the current directory)");
  command->add_option("--python", options->python, "Python with matplotlib")->capture_default_str();
  command->add_option("--threads", options->threads, "Worker threads (0: all cores)")
      ->check(CLI::Range(0, 4096))
      ->capture_default_str();
  command->add_flag("--quiet", options->runs.quiet, "No progress on stderr");
  command->callback([options] { runAdaptive(*options); });
}

}  // namespace radquad
