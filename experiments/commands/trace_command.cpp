// `radquad trace SCENE [--samples N] [--seed S] [--threads T] [--quiet] [--out FILE]`: an
// unbiased Monte Carlo estimate of every patch's mean radiosity with its standard error
// (radiosity/path_tracer.h), the independent reference for `radquad solve`. Prints one JSON
// object on stdout, or writes it atomically to FILE: the options echoed (scene, samples,
// seed), elapsed_seconds, paths, rays {hit, shadow}, truncated_paths and `patches` (scene
// order, the names of `radquad solve`'s): {name, area, mean_radiosity, standard_error}.
// The output does not depend on the thread count (but for elapsed_seconds).
#include <iostream>
#include <memory>
#include <string>

#include "experiments/atomic_file.h"
#include "experiments/commands/commands.h"
#include "experiments/scene_input.h"
#include "experiments/trace_report.h"
#include "kernel/input_error.h"

namespace radquad {
namespace {

struct TraceCommandOptions {
  std::string scene;
  std::string samples = std::to_string(kDefaultTraceSamples);
  std::string seed = "0";
  int threads = 0;
  bool quiet = false;
  std::string out;
};

void runTraceCommand(const TraceCommandOptions& command) {
  TraceOptions options;
  options.samples = parseDecimalOption(command.samples, "--samples", 1, kMaxTraceSamples);
  options.seed = parseDecimalOption(command.seed, "--seed", 0, ~std::uint64_t(0));
  options.threads = command.threads;
  if (!command.out.empty()) checkOutputPath(command.out, "--out", {command.scene});
  const Scene scene = loadScene(command.scene);
  const TraceResult trace = runTrace(scene, options, command.quiet, "radquad trace");

  nlohmann::json out = {
      {"scene", command.scene},
      {"options", {{"samples", options.samples}, {"seed", options.seed}}},
      {"elapsed_seconds", trace.elapsedSeconds},
  };
  out.update(traceCountsJson(trace));
  out["patches"] = tracePatchesJson(scene, trace);
  const std::string text = out.dump(2) + "\n";
  if (command.out.empty()) {
    std::cout << text;
  } else {
    writeFileAtomically(command.out, text);
  }
}

}  // namespace

void addTraceCommand(CLI::App& app) {
  auto options = std::make_shared<TraceCommandOptions>();
  CLI::App* command = app.add_subcommand(
      "trace",
      "Monte Carlo reference: every patch's mean radiosity with its standard error; JSON on "
      "stdout");
  command
      ->add_option("scene", options->scene,
                   "A scene JSON file, or a built-in scene: cornell, slats")
      ->required();
  command
      ->add_option("--samples", options->samples,
                   "Samples (paths) per patch, 1.." + std::to_string(kMaxTraceSamples))
      ->capture_default_str();
  command->add_option("--seed", options->seed, "Seed, a decimal 0..2^64-1")->capture_default_str();
  command->add_option("--threads", options->threads, "Worker threads (0: all cores)")
      ->check(CLI::Range(0, 4096))
      ->capture_default_str();
  command->add_flag("--quiet", options->quiet, "No progress on stderr");
  command->add_option("--out", options->out, "Write the JSON to this file instead of stdout");
  command->callback([options] { runTraceCommand(*options); });
}

}  // namespace radquad
