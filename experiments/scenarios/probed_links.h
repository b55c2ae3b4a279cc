// Partial links as the study keeps them, drawn from its generator (scenario.h) for the gold's
// benchmark and its honesty test: candidate i of `seed` is generateLink(default ranges,
// partial, deriveSeed(seed, {1, i, 0})); a candidate of a wanted occluder kind is kept while
// its kind has fewer than `perKind` links and its visible fraction, by a 6^4 Gauss product
// rule, lies strictly inside (0.05, 0.95).
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "experiments/scenarios/scenario.h"
#include "kernel/coupling.h"

namespace radquad {

struct ProbedLink {
  GeneratedLink generated;
  std::unique_ptr<OccluderScene> scene;
  Link link() const { return Link{generated.receiver, generated.source, scene.get()}; }
};

// In the order drawn; stops when every kind has `perKind` links (or after 100,000
// candidates).
std::vector<ProbedLink> probedPartialLinks(std::uint64_t seed, const std::vector<OccluderKind>& kinds,
                                           int perKind);

}  // namespace radquad
