// A study config (experiments/configs/*.json): which figure, which links, which rules.
// Keys (unknown keys are an error; "_doc" holds free text and is ignored):
//   figure      "fig1" (constant bases, relative error of K[0][0]) or "fig2" (quadratic
//               bases, L1 error bound per source function); required
//   seed        unsigned integer; every link, trial and reference seed derives from it; required
//   classes     {"partial": N}, {"unoccluded": N} and, scene-derived links only,
//               {"singular": N}: links wanted per class; required
//   rules       rule names as `radquad rules` lists them; required
//   trials      independent trials of each random rule per link (default 10)
//   reference   the paper's reference: {"strata_per_axis": 10, "replicates": 10}; the
//               replicates (independent draws) estimate its own standard error
//   gold        the gold reference every rule is scored against (unless --no-gold):
//               {"method": "exact", "tolerance": 1e-9, "exact_tolerance": 3e-4,
//               "max_evaluations": 2000000, "max_exact_occluders": 64, "dense_strata": 16,
//               "dense_replicates": 8} (the study's defaults, studyGoldOptions in
//               reference_estimate.h; reference/gold_reference.h)
//   links       optional: {"scene": NAME or PATH, "degree": 2, "bf_eps": 0.05}: the links of
//               a solve of that scene instead of generated ones (experiments/study/
//               scene_links.h); `geometry` then does not apply
//   visible_fraction  [low, high]: a partial link's reference visible fraction must lie
//               strictly inside (default [0.05, 0.95])
//   max_candidates_per_link  give up on a class after N times its link count of candidates
//               (default 40)
//   geometry    element sizes, distances, orientations, occluders
//   (experiments/scenarios/scenario.h)
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "experiments/scenarios/scenario.h"
#include "experiments/study/reference_estimate.h"
#include "experiments/study/scene_links.h"
#include "reference/gold_reference.h"
#include "reference/stratified_reference.h"

namespace radquad {

enum class StudyFigure { fig1, fig2 };

struct StudyConfig {
  StudyFigure figure = StudyFigure::fig1;
  std::uint64_t seed = 1;
  std::vector<std::pair<StudyClass, int>> classes;  // in the order unoccluded, partial, singular
  std::vector<std::string> rules;
  int trials = 10;
  ReferenceOptions reference;
  GoldOptions gold = studyGoldOptions();
  double minVisibleFraction = 0.05;
  double maxVisibleFraction = 0.95;
  int maxCandidatesPerLink = 40;
  GeometryRanges geometry;
  std::optional<SceneLinkOptions> sceneLinks;

  // The basis degree of the figure: 0 for Figure 1, 2 for Figure 2 (docs/design.md, "The study").
  int degree() const { return figure == StudyFigure::fig1 ? 0 : 2; }
};

StudyConfig parseStudyConfig(const nlohmann::json& value, const std::string& where);
StudyConfig readStudyConfig(const std::filesystem::path& path);
// Everything needed to rerun: the parsed config with every default filled in.
nlohmann::json studyConfigToJson(const StudyConfig& config);

}  // namespace radquad
