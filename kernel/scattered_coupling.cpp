// The scattered coupling path: a general list of 4D points, contracted in blocks of 256 so the
// basis values stay in cache (docs/design.md, "Conventions"; kernel/coupling.h,
// kernel/block_contraction.h).
#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstring>
#include <numbers>

#include "kernel/coupling.h"
#include "kernel/coupling_internal.h"
#include "kernel/legendre_basis.h"

namespace radquad {
using detail::kernelTimesPi;

void CouplingAccumulator::scattered(const Link& link, const LinkSamples& samples, int degree,
                                    LinkIntegral& result) {
  validateBasisDegree(degree);
  const std::size_t count = samples.size();
  placeLink(link, samples.s.data(), samples.t.data(), count, samples.u.data(), samples.v.data(),
            count);
  kernel_.resize(count);
  for (std::size_t k = 0; k < count; ++k) {
    kernel_[k] = kernelTimesPi(
        sourceX_[k] - receiverX_[k], sourceY_[k] - receiverY_[k], sourceZ_[k] - receiverZ_[k],
        sourceReceiverDot_[k] - receiverNormalDot_[k], receiverSourceDot_[k] - sourceNormalDot_[k]);
  }
  result.raysCast = 0;
  result.raysBlocked = 0;
  std::size_t positive = 0;
  if (link.hasOccluders()) {
    for (std::size_t k = 0; k < count; ++k) positive += detail::needsRay(kernel_[k]) ? 1 : 0;
  }
  if (link.hasOccluders() && positive == count) {
    // Every pair faces the other: one ray per point, staged and applied without branches.
    stageRays(count);
    for (std::size_t k = 0; k < count; ++k) {
      rayOriginX_[k] = float(receiverX_[k]);
      rayOriginY_[k] = float(receiverY_[k]);
      rayOriginZ_[k] = float(receiverZ_[k]);
      rayDirectionX_[k] = float(sourceX_[k] - receiverX_[k]);
      rayDirectionY_[k] = float(sourceY_[k] - receiverY_[k]);
      rayDirectionZ_[k] = float(sourceZ_[k] - receiverZ_[k]);
    }
    traceStagedRays(link, count, result);
  } else if (link.hasOccluders()) {
    segments_.resize(count);
    rayPairs_.resize(count);
    std::size_t rays = 0;
    for (std::size_t k = 0; k < count; ++k) {
      if (!detail::needsRay(kernel_[k])) continue;
      segments_.set(rays, receiverX_[k], receiverY_[k], receiverZ_[k], sourceX_[k] - receiverX_[k],
                    sourceY_[k] - receiverY_[k], sourceZ_[k] - receiverZ_[k]);
      rayPairs_[rays++] = std::uint32_t(k);
    }
    segments_.resize(rays);
    rayPairs_.resize(rays);
    castRays(link, kernel_, result);
  }

  contraction_.begin(degree);
  weightedKernel_.resize(detail::kPointBlock);
  for (std::size_t start = 0; start < count; start += detail::kPointBlock) {
    const std::size_t rows = std::min(detail::kPointBlock, count - start);
    const double* __restrict w = samples.weight.data() + start;
    const double* __restrict g = kernel_.data() + start;
    double* __restrict wg = weightedKernel_.data();
    for (std::size_t row = 0; row < rows; ++row) wg[row] = w[row] * g[row];
    contraction_.accumulate(rows, samples.s.data() + start, samples.t.data() + start,
                            samples.u.data() + start, samples.v.data() + start, wg);
  }
  contraction_.end(result.coupling);
  scaleCoupling(link, 1.0, result);
  result.kernelEvaluations = count;
}

}  // namespace radquad
