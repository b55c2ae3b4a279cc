// `radquad solve SCENE --degree D --rules fixed|adaptive|adaptive-novis [--threshold T]
// [--compare] [--render out.png] [--bf-eps E] [--min-area A]`: solves a scene with the
// hierarchical Galerkin radiosity solver and prints one JSON object on stdout (options
// echoed, kernel evaluations, links by class, elements, iterations, time, and every patch's
// mean radiosity; with --compare, the same scene solved with fixed rules and the relative L2
// difference of the two solutions; with --verify N, every patch's mean radiosity against a
// Monte Carlo reference of N samples per patch, radiosity/path_tracer.h); progress goes to
// stderr.
#include <tbb/global_control.h>

#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "experiments/atomic_file.h"
#include "experiments/commands/commands.h"
#include "experiments/scene_input.h"
#include "experiments/solve_report.h"
#include "experiments/trace_report.h"
#include "kernel/input_error.h"
#include "radiosity/render.h"
#include "radiosity/solver.h"

namespace radquad {
namespace {

// The command line binds straight into the solver's options; the names given as text (rules,
// dropped orders) and the memory budget in MiB are resolved by runSolve.
struct SolveCommandOptions {
  std::string scene;
  SolverOptions solver;
  std::string rules = ruleChoiceName(RuleChoice::kFixed);
  std::string droppedOrders = droppedOrdersName(DroppedOrders::kTruncated);
  std::size_t maxMemoryMiB = SolverOptions{}.maxMemoryBytes >> 20;
  bool compare = false;
  bool noNearField = false;
  std::string renderPath;
  int threads = 0;
  bool quiet = false;
  std::string verifySamples;  // empty: no verification
  std::string verifySeed = "0";
};

nlohmann::json vectorJson(const Eigen::Vector3d& v) {
  return {v.x(), v.y(), v.z()};
}

RuleChoice parseRuleChoice(const std::string& name) {
  for (RuleChoice choice :
       {RuleChoice::kFixed, RuleChoice::kAdaptive, RuleChoice::kAdaptiveNoVisibility}) {
    if (name == ruleChoiceName(choice)) return choice;
  }
  throw InputError("--rules " + name +
                   ": unknown rule choice (valid: fixed, adaptive, adaptive-novis)");
}

void runSolve(const SolveCommandOptions& command) {
  SolverOptions options = command.solver;
  if (options.degree < 0 || options.degree > 3) {
    throw InputError("--degree " + std::to_string(options.degree) + ": must be 0, 1, 2 or 3");
  }
  options.rules = parseRuleChoice(command.rules);
  if (!(options.errThres >= 0.0) || !std::isfinite(options.errThres)) {
    throw InputError("--threshold: must be a finite number >= 0");
  }
  if (!(options.kernelCurvature >= 0.0) || !std::isfinite(options.kernelCurvature)) {
    throw InputError("--kernel-curvature: must be a finite number >= 0 (0: no kernel check)");
  }
  if (command.droppedOrders == droppedOrdersName(DroppedOrders::kAliased)) {
    options.droppedOrders = DroppedOrders::kAliased;
  } else if (command.droppedOrders == droppedOrdersName(DroppedOrders::kTruncated)) {
    options.droppedOrders = DroppedOrders::kTruncated;
  } else {
    throw InputError("--dropped-orders " + command.droppedOrders +
                     ": unknown treatment (valid: truncated, aliased)");
  }
  if (!(options.bfEpsilon > 0.0)) throw InputError("--bf-eps: must be > 0");
  if (!(options.minArea >= 0.0)) throw InputError("--min-area: must be >= 0 (0: automatic)");
  if (!(options.partialFactor >= 1.0)) throw InputError("--partial-factor: must be >= 1");
  if (!(options.variationEpsilon >= 0.0)) throw InputError("--variation-eps: must be >= 0 (0: off)");
  if (!(options.tolerance > 0.0)) throw InputError("--tolerance: must be > 0");
  options.maxMemoryBytes = command.maxMemoryMiB << 20;
  options.nearField = !command.noNearField;
  TraceOptions verify;
  verify.seed = parseDecimalOption(command.verifySeed, "--verify-seed", 0, ~std::uint64_t(0));
  if (!command.verifySamples.empty()) {
    verify.samples = parseDecimalOption(command.verifySamples, "--verify", 1, kMaxTraceSamples);
  }
  if (!command.renderPath.empty()) {
    checkOutputPath(command.renderPath, "--render", {command.scene});
  }
  const Scene scene = loadScene(command.scene);

  std::optional<tbb::global_control> threadLimit;
  if (command.threads > 0) {
    threadLimit.emplace(tbb::global_control::max_allowed_parallelism, std::size_t(command.threads));
  }
  if (!command.quiet) {
    options.linkingProgress = [](const LinkingProgress& progress) {
      std::fprintf(stderr,
                   "radquad solve: initial linking: %zu of %zu patches, %zu links, %zu "
                   "classified, %.1f s\n",
                   progress.patchesDone, progress.patches, progress.links, progress.classified,
                   progress.elapsedSeconds);
    };
    options.refinementProgress = [](const RefinementProgress& progress) {
      std::fprintf(stderr,
                   "radquad solve: refinement: wave %d, %zu links split, %zu elements, %zu "
                   "links, %.1f s\n",
                   progress.wave, progress.splits, progress.elements, progress.links,
                   progress.elapsedSeconds);
    };
    options.progress = [](const SolveProgress& progress) {
      if (progress.elapsedSeconds < 1.0) return;
      std::fprintf(stderr,
                   "radquad solve: iteration %d: %zu links, %zu elements, %llu kernel "
                   "evaluations, change %.3g, %.1f s\n",
                   progress.iteration, progress.activeLinks, progress.elements,
                   static_cast<unsigned long long>(progress.kernelEvaluations), progress.change,
                   progress.elapsedSeconds);
    };
  }
  if (!command.quiet) {
    std::fprintf(stderr, "radquad solve: %s, degree %d, %s rules\n", command.scene.c_str(),
                 options.degree, ruleChoiceName(options.rules));
  }
  Solver solver(scene, options);
  solver.solve();
  const SolveStatistics& statistics = solver.statistics();
  const Hierarchy& hierarchy = solver.hierarchy();

  nlohmann::json patches = nlohmann::json::array();
  std::vector<Eigen::Vector3d> solved;
  for (std::size_t p = 0; p < scene.patches.size(); ++p) {
    solved.push_back(hierarchy[hierarchy.root(int(p))].meanRadiosity());
    patches.push_back({{"name", scene.patches[p].name},
                       {"area", scene.patches[p].patch.area},
                       {"mean_radiosity", vectorJson(solved.back())}});
  }
  nlohmann::json out = solveStatisticsJson(solver);
  out["scene"] = command.scene;
  out["options"] = solverOptionsJson(solver);
  out["patches"] = patches;
  if (command.compare) {
    if (!command.quiet) std::fprintf(stderr, "radquad solve: the same scene with fixed rules\n");
    SolverOptions fixedOptions = options;
    fixedOptions.rules = RuleChoice::kFixed;
    Solver fixed(scene, fixedOptions);
    fixed.solve();
    out["comparison"] = comparisonJson(solver, fixed);
    out["comparison"]["fixed_elapsed_seconds"] = fixed.statistics().elapsedSeconds;
    out["comparison"]["fixed_coupling_seconds"] = fixed.statistics().couplingSeconds;
  }
  if (statistics.formFactorSums.violations > 0) {
    std::fprintf(stderr,
                 "radquad solve: warning: %zu elements have form factor sums above 1 + %g (largest "
                 "%.4g, on %s): some couplings create energy\n",
                 statistics.formFactorSums.violations, kFormFactorSumTolerance,
                 statistics.formFactorSums.maximum,
                 describePatch(scene, std::size_t(statistics.formFactorSums.patch)).c_str());
  }
  if (!statistics.converged) {
    // The JSON (with "converged": false and the reason) still goes to stdout for diagnosis;
    // no render is written and the exit status is 3.
    std::cout << out.dump(2) << "\n";
    throw ComputationError(command.scene + ": the solve did not converge: " + statistics.failure);
  }
  if (!command.verifySamples.empty()) {
    out["verification"] = verifySolution(scene, solved, verify, command.quiet);
  }
  if (!command.renderPath.empty()) {
    const Camera camera = scene.camera ? *scene.camera : defaultCamera(scene);
    writeFileAtomically(command.renderPath, encodePng(renderRadiosity(hierarchy, camera)));
    out["render"] = command.renderPath;
  }
  std::cout << out.dump(2) << "\n";
}

}  // namespace

void addSolveCommand(CLI::App& app) {
  auto options = std::make_shared<SolveCommandOptions>();
  CLI::App* command = app.add_subcommand(
      "solve", "Solve a scene with hierarchical Galerkin radiosity; prints JSON on stdout");
  command
      ->add_option("scene", options->scene,
                   "A scene JSON file, or a built-in scene: cornell, slats")
      ->required();
  command->add_option("--degree", options->solver.degree, "Basis degree d, 0..3")->capture_default_str();
  command
      ->add_option("--rules", options->rules,
                   "Gauss rule choice per link: fixed ((d+1)^4 points), adaptive (Gershbein 1995, "
                   "Figure 4), adaptive-novis (without the partial-visibility point)")
      ->capture_default_str();
  command
      ->add_option("--threshold", options->solver.errThres,
                   "ErrThres of the adaptive rules, as a fraction of the scene's emitted "
                   "radiosity (emitted power over total area)")
      ->capture_default_str();
  command
      ->add_option("--kernel-curvature", options->solver.kernelCurvature,
                   "Adaptive rules: a one-point source axis whose estimated midpoint error "
                   "(relative) exceeds this gets two points; 0: Figure 4's choice alone")
      ->capture_default_str();
  command
      ->add_option("--dropped-orders", options->droppedOrders,
                   "Adaptive rules: source orders a reduced rule does not keep are truncated "
                   "(dropped) or aliased (gathered through the rule's points, the report's "
                   "reading)")
      ->capture_default_str();
  command->add_flag("--compare", options->compare,
                    "Also solve with fixed rules and report the relative L2 difference");
  command->add_option("--render", options->renderPath,
                      "Write a PNG of the solution from the scene's camera");
  command
      ->add_option("--bf-eps", options->solver.bfEpsilon,
                   "BF oracle threshold, relative to the emitted power per unit scene area")
      ->capture_default_str();
  command
      ->add_option("--min-area", options->solver.minArea,
                   "Smallest element area to split (scene units^2; 0: 1e-4 of the largest patch)")
      ->capture_default_str();
  command
      ->add_option("--variation-eps", options->solver.variationEpsilon,
                   "Split a link at its source where the source's radiosity beyond its "
                   "polynomial can move the receiver's by more than this fraction (0: off)")
      ->capture_default_str();
  command
      ->add_option("--partial-factor", options->solver.partialFactor,
                   "Multiplier of a partially visible link's transfer estimate")
      ->capture_default_str();
  command
      ->add_option("--tolerance", options->solver.tolerance,
                   "Stop when the relative L2 change of patch radiosity is below this")
      ->capture_default_str();
  command->add_option("--max-iterations", options->solver.maxIterations, "Iteration cap")
      ->check(CLI::Range(1, 1000000))
      ->capture_default_str();
  command
      ->add_option("--max-elements", options->solver.maxElements,
                   "Element budget: the solve fails (exit 3) when refinement would exceed it")
      ->check(CLI::Range(std::size_t(1), std::size_t(1) << 40))
      ->capture_default_str();
  command
      ->add_option("--max-links", options->solver.maxLinks,
                   "Link budget: the solve fails (exit 3) when refinement would exceed it")
      ->check(CLI::Range(std::size_t(1), std::size_t(1) << 40))
      ->capture_default_str();
  command
      ->add_option("--max-memory", options->maxMemoryMiB,
                   "Memory budget in MiB (default: 3/4 of the machine's or the control group's memory): the solve fails "
                   "(exit 3) when the process's resident memory exceeds it")
      ->check(CLI::Range(std::size_t(1), std::size_t(1) << 30))
      ->capture_default_str();
  command->add_flag("--no-near-field", options->noNearField,
                    "Integrate links between near elements with their product rules too "
                    "(to measure what the near field changes)");
  command->add_option("--threads", options->threads, "Worker threads (0: all cores)")
      ->check(CLI::Range(0, 4096))
      ->capture_default_str();
  command->add_flag("--quiet", options->quiet, "No progress on stderr");
  command->add_option("--verify", options->verifySamples,
                      "Also trace the scene with N Monte Carlo samples per patch and compare "
                      "(adds `verification`)");
  command->add_option("--verify-seed", options->verifySeed, "Seed of --verify, a decimal 0..2^64-1")
      ->capture_default_str();
  command->callback([options] { runSolve(*options); });
}

}  // namespace radquad
