// The study's per-link outputs: the "per_link" scores of a class in the table (four
// significant digits, for reading and plotting), and the per-link table of
// `radquad study --links-out` (linkTableLines, declared in study_runner.h: every scored link's
// geometry, gold and every rule's coupling, one JSON object per line).
#pragma once

#include <nlohmann/json.hpp>

#include "experiments/study/study_runner.h"

namespace radquad {

// Every link's own scores, in candidate order (rules in the order of "rules").
nlohmann::json perLinkScores(const ClassRun& classRun, bool gold, bool fig2);

}  // namespace radquad
