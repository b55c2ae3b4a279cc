// `radquad reference LINK.json [--degree D] [--seed S] [--replicates R] [--gold
// [--gold-method auto|exact|stratified] [--gold-tolerance T]] [--quiet]`: the paper's
// 10,000-sample stratified reference of one link with its standard error, and optionally a
// gold reference to measure how far it is off; prints one JSON object on stdout.
//
// Output keys: options echoed (link, degree, seed, replicates), `form_factor`, `coupling`,
// `standard_error` = {`form_factor`, `coupling`} (reference/stratified_reference.h says how
// it is estimated), `kernel_evaluations`, `visible_fraction`; with --gold, `gold` =
// {method, form_factor, coupling, error = {kind, form_factor, coupling}, converged,
// kernel_evaluations, and gauss_points, tolerance, lambert_check (Gauss) or tolerance,
// receiver_points, shaft_occluders, outer_method, critical_segments, unoccluded_apart, confirmed (exact visibility)} and `reference_minus_gold` = {form_factor,
// max_abs_coupling, form_factor_in_standard_errors}. A gold that does not reach its tolerance
// within its budget is printed too, and the exit status is 3.
#include <cstdio>
#include <iostream>
#include <memory>
#include <string>

#include "experiments/commands/commands.h"
#include "experiments/json_input.h"
#include "experiments/link_reports.h"
#include "experiments/trace_report.h"
#include "kernel/input_error.h"
#include "reference/gold_reference.h"
#include "reference/stratified_reference.h"

namespace radquad {
namespace {

struct ReferenceCommandOptions {
  std::string linkPath;
  int degree = 0;
  std::string seedText = "0";
  std::uint64_t seed = 0;
  int replicates = ReferenceOptions{}.replicates;
  bool gold = false;
  std::string goldMethod = goldMethodName(GoldOptions{}.method);
  double goldTolerance = GoldOptions{}.exactTolerance;
  bool quiet = false;
};

void runReference(ReferenceCommandOptions options) {
  options.seed = parseDecimalOption(options.seedText, "--seed", 0, ~std::uint64_t(0));
  GoldOptions goldOptions;
  goldOptions.method = parseGoldMethod(options.goldMethod, "--gold-method");
  goldOptions.exactTolerance = options.goldTolerance;
  if (!options.quiet) {
    goldOptions.progress = [](std::uint64_t points, double seconds) {
      std::fprintf(stderr, "radquad reference: gold: %llu receiver points, %.1f s\n",
                   static_cast<unsigned long long>(points), seconds);
    };
  }
  const LinkGeometry description = readLinkFile(options.linkPath);
  ReferenceReportOptions report;
  report.degree = options.degree;
  report.seed = options.seed;
  report.replicates = options.replicates;
  report.gold = options.gold;
  report.goldOptions = goldOptions;
  const nlohmann::json out = referenceReport(description, report, options.linkPath, &std::cerr);
  std::cout << out.dump(2) << "\n";
  if (out.contains("gold") && !out["gold"]["converged"].get<bool>()) {
    // The JSON (with "converged": false) still goes to stdout for diagnosis; exit status 3.
    char tolerance[32];
    std::snprintf(tolerance, sizeof tolerance, "%g", options.goldTolerance);
    throw ComputationError(options.linkPath + ": the gold did not reach its tolerance (" +
                           tolerance + ") within its evaluation budget");
  }
}

}  // namespace

void addReferenceCommand(CLI::App& app) {
  auto options = std::make_shared<ReferenceCommandOptions>();
  CLI::App* command = app.add_subcommand(
      "reference",
      "The paper's 10,000-sample stratified reference of one link with its standard error "
      "(and, with --gold, a gold reference); prints JSON on stdout");
  command
      ->add_option("link", options->linkPath,
                   "LINK.json: {\"receiver\": PATCH, \"source\": PATCH, \"occluders\": [PATCH...]}")
      ->required();
  command->add_option("--degree", options->degree, "Basis degree d, 0..8")->capture_default_str();
  command->add_option("--seed", options->seedText, "Seed of the reference draw, a decimal 0..2^64-1")
      ->capture_default_str();
  command
      ->add_option("--replicates", options->replicates,
                   "Independent draws for the standard error (2..100000)")
      ->capture_default_str();
  command->add_flag("--gold", options->gold,
                    "Also compute a gold reference (Gauss of rising order, exact visibility or "
                    "dense stratified)");
  command
      ->add_option("--gold-method", options->goldMethod,
                   "auto: Gauss products where no occluder meets the link's shaft, exact "
                   "visibility where one does (dense stratified beyond 64 occluder polygons); "
                   "exact or stratified: that gold on any link")
      ->check(CLI::IsMember({"auto", "exact", "stratified"}))
      ->capture_default_str();
  command
      ->add_option("--gold-tolerance", options->goldTolerance,
                   "Exact gold: estimated error relative to the largest |K| entry, in (0, 1)")
      ->check(CLI::Range(1e-15, 0.5))
      ->capture_default_str();
  command->add_flag("--quiet", options->quiet,
                    "No progress on stderr (the exact gold reports its receiver points about once "
                    "a second once it has run a second)");
  command->callback([options] { runReference(*options); });
}

}  // namespace radquad
