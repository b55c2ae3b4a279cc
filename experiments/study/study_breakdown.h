// Where each rule wins: a class's scores by occluder kind (scene-derived links: by scene) and
// by distance band (distance of the centres over the longest side), each with every rule's
// paired ratio of means to FullGauss's and its 95% bootstrap interval over the group's links
// (study_statistics.h), and each rule's largest link's share of its mean; the "breakdown" of
// the study table (docs/cli.md, "The tables").
#pragma once

#include <cstddef>
#include <cstdint>
#include <nlohmann/json.hpp>

#include "experiments/study/study_runner.h"

namespace radquad {

// `rules` scored rules; `fullGauss` their index of FullGauss, -1 when it is not scored (no
// ratios then); `seed` the class's bootstrap seed (bootstrapSeed, study_statistics.h).
nlohmann::json studyBreakdown(const ClassRun& classRun, std::size_t rules, bool gold, bool fig2,
                              int fullGauss, std::uint64_t seed);

}  // namespace radquad
