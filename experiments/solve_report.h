// What a solve reports (docs/cli.md, "solve"): the options it ran with, its statistics and
// the comparison of two solutions, written once for `radquad solve` and `radquad adaptive`.
#pragma once

#include <nlohmann/json.hpp>

#include "radiosity/hierarchy.h"
#include "radiosity/scene.h"
#include "radiosity/solver.h"

namespace radquad {

// The options that shaped the solution: degree, rules and every setting of the rule choice,
// the oracle, the iteration and the budgets ("min_area" as the solver resolved it).
nlohmann::json solverOptionsJson(const Solver& solver);

// The solve's statistics: kernel evaluations of the product rules (all, recomputations', the
// kernel check's), near-field links and points, coupling computations, links by class, rays,
// elements, iterations (with the final change, error estimate and extrapolations),
// convergence and its failure, receiver sums, times and the coupling store's memory.
// Keys that change from run to run: kSolveTimingKeys.
nlohmann::json solveStatisticsJson(const Solver& solver);

// The keys of solveStatisticsJson that are measurements of time.
inline const char* const kSolveTimingKeys[] = {"elapsed_seconds", "coupling_seconds",
                                               "kernel_evaluations_per_second"};

// A solution against the fixed rules' solution of the same scene: the relative L2 difference,
// the largest per-patch difference, the fixed rules' kernel evaluations and near-field points,
// and the ratio of kernel evaluations (the near field integrates alike with either rule choice).
nlohmann::json comparisonJson(const Solver& solver, const Solver& fixed);

// {"value": relative difference, "patch": name, "channel": "red" | "green" | "blue"}.
nlohmann::json patchDifferenceJson(const Hierarchy::PatchDifference& difference,
                                   const Scene& scene);

}  // namespace radquad
