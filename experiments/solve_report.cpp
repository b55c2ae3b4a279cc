#include "experiments/solve_report.h"

namespace radquad {

nlohmann::json solverOptionsJson(const Solver& solver) {
  const SolverOptions& options = solver.options();
  return {{"degree", options.degree},
          {"rules", ruleChoiceName(options.rules)},
          {"threshold", options.errThres},
          {"kernel_curvature", options.kernelCurvature},
          {"dropped_orders", droppedOrdersName(options.droppedOrders)},
          {"bf_eps", options.bfEpsilon},
          {"min_area", solver.minArea()},
          {"variation_eps", options.variationEpsilon},
          {"partial_factor", options.partialFactor},
          {"tolerance", options.tolerance},
          {"max_iterations", options.maxIterations},
          {"max_elements", options.maxElements},
          {"max_links", options.maxLinks},
          {"max_memory_mib", options.maxMemoryBytes >> 20},
          {"near_field", options.nearField},
          {"iteration", "jacobi"}};
}

nlohmann::json solveStatisticsJson(const Solver& solver) {
  const SolveStatistics& s = solver.statistics();
  const Scene& scene = solver.hierarchy().scene();
  return {
      {"kernel_evaluations", s.kernelEvaluations},
      {"coupling_computations", s.couplingComputations},
      {"recomputations", s.recomputations},
      {"recomputation_kernel_evaluations", s.recomputationEvaluations},
      {"near_field_links", s.nearFieldLinks},
      {"near_field_points", s.nearFieldPoints},
      {"rule_check_kernel_evaluations", s.ruleCheckEvaluations},
      {"links",
       {{"unoccluded", s.unoccludedLinks},
        {"partial", s.partialLinks},
        {"occluded", s.occludedLinks},
        {"refined", s.refinedLinks}}},
      {"rays", {{"classification", s.classificationRays}, {"integration", s.integrationRays}}},
      {"elements", solver.hierarchy().size()},
      {"iterations", s.iterations},
      {"converged", s.converged},
      {"failure", s.failure},
      {"form_factor_sums",
       {{"maximum", s.formFactorSums.maximum},
        {"patch", s.formFactorSums.patch >= 0
                      ? nlohmann::json(scene.patches[std::size_t(s.formFactorSums.patch)].name)
                      : nlohmann::json(nullptr)},
        {"tolerance", kFormFactorSumTolerance},
        {"violations", s.formFactorSums.violations}}},
      {"final_change", s.finalChange},
      {"final_error", s.finalError},
      {"extrapolations", s.extrapolations},
      {"elapsed_seconds", s.elapsedSeconds},
      {"coupling_seconds", s.couplingSeconds},
      {"coupling_store_bytes", s.couplingStoreBytes},
      {"kernel_evaluations_per_second",
       s.elapsedSeconds > 0.0 ? double(s.kernelEvaluations) / s.elapsedSeconds : 0.0},
  };
}

namespace {

double ratio(std::uint64_t numerator, std::uint64_t denominator) {
  return denominator > 0 ? double(numerator) / double(denominator) : 0.0;
}

}  // namespace

nlohmann::json comparisonJson(const Solver& solver, const Solver& fixed) {
  const auto [difference, norm] = solver.hierarchy().l2Difference(fixed.hierarchy());
  const SolveStatistics& s = solver.statistics();
  const SolveStatistics& f = fixed.statistics();
  return {
      {"relative_l2_difference", norm > 0.0 ? difference / norm : 0.0},
      {"largest_patch_difference",
       patchDifferenceJson(solver.hierarchy().largestPatchDifference(fixed.hierarchy()),
                           solver.hierarchy().scene())},
      {"fixed_kernel_evaluations", f.kernelEvaluations},
      {"fixed_near_field_points", f.nearFieldPoints},
      {"evaluation_ratio", ratio(f.kernelEvaluations, s.kernelEvaluations)},
  };
}

nlohmann::json patchDifferenceJson(const Hierarchy::PatchDifference& difference,
                                   const Scene& scene) {
  if (difference.patch < 0) return {{"value", 0.0}, {"patch", nullptr}, {"channel", nullptr}};
  static const char* const kChannels[] = {"red", "green", "blue"};
  return {{"value", difference.value},
          {"patch", scene.patches[std::size_t(difference.patch)].name},
          {"channel", kChannels[difference.channel]}};
}

}  // namespace radquad
