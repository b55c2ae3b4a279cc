// Whether two patches interpenetrate: their interiors share a segment (they cross) or, in one
// plane, a region of positive area (they overlap or coincide). Touching along an edge or at a
// corner, or an edge lying on the other patch (a block standing on a floor), is not
// interpenetration: such links are legal, with a singular but integrable kernel.
//
// Between interpenetrating patches the irradiance kernel has a non-integrable singularity
// along the shared set (|x - x'| -> 0 with both cosines positive on one side), so no rule
// can integrate such a link; inputs are checked with this before any work.
#pragma once

#include <optional>
#include <string>

#include "kernel/patch.h"

namespace radquad {

// A description of how a and b interpenetrate ("cross along a segment of length L",
// "overlap in their common plane over an area A"), or nothing when they do not. Lengths and
// areas below 1e-9 of the patches' size are treated as touching.
std::optional<std::string> patchesInterpenetrate(const Patch& a, const Patch& b);

}  // namespace radquad
