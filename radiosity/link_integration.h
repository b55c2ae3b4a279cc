// Integration of one link's coupling K (DESIGN.md) with a Gauss product rule
// {Rs, Rt, Su, Sv}, with a subdivision near the kernel's singularity.
//
// Where two elements touch (a shared edge or corner, a block standing on a floor), the
// kernel 1/r^2 is unbounded and a product rule over the whole pair converges only like the
// size of the touching region: a 1-point rule on two unit squares sharing an edge gives
// F = 1/pi instead of 0.2000. Such a pair is split into its 4 x 4 quadrant pairs, recursively
// up to `depth` levels where the quadrants still touch, each piece integrated with the same
// rule, and the pieces are put together exactly with the two-scale matrices:
//   K_parent = sum_{c, c'} T_c^T K_(c, c') T_c'    (radiosity/two_scale.h).
#pragma once

#include <array>
#include <cstdint>

#include "kernel/coupling.h"
#include "radiosity/gauss_tables.h"
#include "radiosity/two_scale.h"

namespace radquad {

// Whether a corner of either parallelogram lies on the other (within a relative tolerance).
bool elementsTouch(const Patch& a, const Patch& b);

// Elements whose centres are closer than kNearFactor times the sum of their radii, or that
// touch: there the kernel varies too fast for a product rule over the whole pair.
inline constexpr double kNearFactor = 1.0;
bool elementsNear(const Patch& a, const Patch& b);

struct LinkIntegrationResult {
  Eigen::MatrixXd coupling;
  std::uint64_t kernelEvaluations = 0;
  std::uint64_t raysCast = 0;
};

void integrateLink(const Link& link, const std::array<int, 4>& rule, const GaussTables& tables,
                   const TwoScale& twoScale, int depth, CouplingAccumulator& accumulator,
                   LinkIntegrationResult& result);

}  // namespace radquad
