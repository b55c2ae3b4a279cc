// The measurements of `radquad adaptive` (experiments/commands/adaptive_command.cpp): the
// adaptive Gauss rules of Gershbein 1995 against fixed rules in the radiosity solver.
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "radiosity/solver.h"

namespace radquad {

struct AdaptiveRunOptions {
  double threshold = kDefaultErrThres;  // ErrThres of the table and the plate
  // The table's BF threshold: twice the solver's default (SolverOptions::bfEpsilon), so that
  // its timing repeats of every configuration fit the main job (the savings are a property of
  // the rules); the solver's other settings are its defaults.
  double bfEpsilon = 0.1;
  std::vector<int> degrees = {1, 2, 3};
  std::vector<std::string> scenes = {"cornell", "slats"};
  // The ErrThres curve: one scene and degree, coarser refinement to keep it short.
  std::vector<double> sweepThresholds = {1e-3, 1e-2, 3e-2, 0.05, 0.1, 0.3, 1.0, 3.0};
  std::string sweepScene = "cornell";
  int sweepDegree = 3;
  double sweepBfEpsilon = 0.3;
  // Plate 1: the cubic cornell scene (from the table's runs) rendered three ways.
  std::string plateScene = "cornell";
  int plateDegree = 3;
  double differenceScale = 10.0;  // difference images show |B - B_fixed| times this
  // Each table configuration is solved this many times (interleaved); its times are the
  // fastest, as the machine's other load only ever adds time.
  int timingRepeats = 3;
  bool quiet = false;
};

// Runs the table, the sweep and the plate; writes the plate's PNGs (adaptive-novis.png,
// adaptive.png, fixed.png, and difference-adaptive-novis.png, difference-adaptive.png, all
// at the fixed render's exposure) into plateDir; returns the JSON of results/adaptive.json.
nlohmann::json runAdaptiveExperiments(const AdaptiveRunOptions& options,
                                      const std::filesystem::path& plateDir);

}  // namespace radquad
