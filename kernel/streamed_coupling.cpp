// The streamed coupling path (kernel/coupling.h): points of equal weight come from a
// PointStream block by block, and each block of 256 goes through one fused pass: draw,
// place on both patches, evaluate G, stage its rays straight into the segment packets and
// trace them (OccluderScene::traceMasking), drop the points whose G V is zero, contract (kernel/block_contraction.h).
// The sum, the rays and the ray counts are those of scattered() on the same points; only
// the order of the additions differs (tests/kernel/coupling_paths_test.cpp).
#include <algorithm>
#include <cmath>
#include <numbers>
#if defined(__AVX512F__)
#include <immintrin.h>
#endif

#include "kernel/coupling.h"
#include "kernel/coupling_internal.h"
#include "kernel/legendre_basis.h"

namespace radquad {

using detail::kernelTimesPi;
using detail::kPointBlock;
using detail::PatchFrame;

namespace {

// Columns of one block, kPointBlock entries each.
enum Column { kS, kT, kU, kV, kKernel, kColumns };

// Places point k of the block on both patches and evaluates G pi (kernelTimesPi); with
// kStage, also writes its segment to lane k % 16 of packet k / 16 exactly as
// SegmentBatch::set does (float origin x and direction x' - x, tfar 1 - epsilon). Returns how
// many points have a positive kernel. The frames come by value so that the loop keeps them in
// registers; the inner loop over a packet's 16 lanes vectorises.
template <bool kStage>
std::size_t placeAndEvaluate(const PatchFrame receiverFrame, const PatchFrame sourceFrame,
                             std::size_t rows, double* const (&column)[kColumns],
                             SegmentPacket* packets) {
  const double* __restrict ps = column[kS];
  const double* __restrict pt = column[kT];
  const double* __restrict pu = column[kU];
  const double* __restrict pv = column[kV];
  double* __restrict g = column[kKernel];
  std::size_t positive = 0;
  for (std::size_t first = 0; first < rows; first += 16) {
    const std::size_t lanes = std::min<std::size_t>(16, rows - first);
    SegmentPacket* packet = kStage ? packets + first / 16 : nullptr;
    // The columns never overlap (GCC does not see it through the restrict locals).
#pragma GCC ivdep
    for (std::size_t lane = 0; lane < lanes; ++lane) {
      const std::size_t k = first + lane;
      double rx, ry, rz, receiverOwn, receiverOther, sx, sy, sz, sourceOwn, sourceOther;
      receiverFrame.place(ps[k], pt[k], rx, ry, rz, receiverOwn, receiverOther);
      sourceFrame.place(pu[k], pv[k], sx, sy, sz, sourceOwn, sourceOther);
      const double kernel = kernelTimesPi(sx - rx, sy - ry, sz - rz, sourceOther - receiverOwn,
                                          receiverOther - sourceOwn);
      g[k] = kernel;
      positive += detail::needsRay(kernel) ? 1 : 0;
      if constexpr (kStage) {
        packet->org_x[lane] = float(rx);
        packet->org_y[lane] = float(ry);
        packet->org_z[lane] = float(rz);
        packet->dir_x[lane] = float(sx - rx);
        packet->dir_y[lane] = float(sy - ry);
        packet->dir_z[lane] = float(sz - rz);
        packet->tfar[lane] = 1.0f - kSegmentEpsilon;
      }
    }
  }
  return positive;
}

// Moves the points whose kernel is nonzero to the front of the columns s, t, u, v, g, in
// order, and returns how many there are. AVX-512 compresses eight points per instruction and
// column; elsewhere (and for the last rows) a branch-free scalar loop does the same.
std::size_t keepNonzero(std::size_t rows, double* s, double* t, double* u, double* v, double* g) {
  std::size_t kept = 0, k = 0;
#if defined(__AVX512F__)
  for (; k + 8 <= rows; k += 8) {
    // Unordered-or-not-equal, as `!= 0.0` below. Writing 8 lanes at kept <= k only
    // overwrites rows already read.
    const __mmask8 nonzero =
        _mm512_cmp_pd_mask(_mm512_loadu_pd(g + k), _mm512_setzero_pd(), _CMP_NEQ_UQ);
    for (double* column : {s, t, u, v, g}) {
      _mm512_storeu_pd(column + kept,
                       _mm512_maskz_compress_pd(nonzero, _mm512_loadu_pd(column + k)));
    }
    kept += std::size_t(__builtin_popcount(nonzero));
  }
#endif
  for (; k < rows; ++k) {
    const double gk = g[k];
    s[kept] = s[k];
    t[kept] = t[k];
    u[kept] = u[k];
    v[kept] = v[k];
    g[kept] = gk;
    kept += gk != 0.0 ? 1 : 0;
  }
  return kept;
}

}  // namespace

void CouplingAccumulator::streamed(const Link& link, const PointStream& points, int degree,
                                   LinkIntegral& result) {
  validateBasisDegree(degree);
  const std::size_t count = points.size();
  const Patch& r = link.receiver;
  const Patch& s = link.source;
  const PatchFrame receiverFrame(r, s.normal), sourceFrame(s, r.normal);
  const bool occluded = link.hasOccluders();
  streamBlock_.resize(kColumns * kPointBlock);
  double* column[kColumns];
  for (int c = 0; c < kColumns; ++c) column[c] = streamBlock_.data() + c * kPointBlock;
  double* __restrict ps = column[kS];
  double* __restrict pt = column[kT];
  double* __restrict pu = column[kU];
  double* __restrict pv = column[kV];
  double* __restrict g = column[kKernel];
  if (occluded) rayPairs_.resize(kPointBlock);
  contraction_.begin(degree);
  std::uint64_t cast = 0, blocked = 0;

  for (std::size_t start = 0; start < count; start += kPointBlock) {
    const std::size_t rows = std::min(kPointBlock, count - start);
    points.fill(start, rows, ps, pt, pu, pv);
    if (occluded) segments_.resize(rows);
    const std::size_t positive =
        occluded
            ? placeAndEvaluate<true>(receiverFrame, sourceFrame, rows, column, segments_.packets())
            : placeAndEvaluate<false>(receiverFrame, sourceFrame, rows, column, nullptr);
    std::size_t kept = rows;
    if (occluded) {
      // One ray per point whose unoccluded kernel is positive, already in the packets.
      std::size_t rays = rows;
      if (positive == rows) {
        blocked += link.occluders->traceMasking(segments_, g);
      } else {
        // Keep only the rays of positive kernels, in order (as scattered() casts them).
        rays = 0;
        for (std::size_t k = 0; k < rows; ++k) {
          if (!detail::needsRay(g[k])) continue;
          segments_.move(k, rays);
          rayPairs_[rays++] = std::uint32_t(k);
        }
        segments_.resize(rays);
        blocked += link.occluders->traceMasking(segments_, rayPairs_.data(), g);
      }
      cast += rays;
    }
    if (occluded || positive < rows) {
      // Points with G V = 0 add nothing: contract only the others (in order).
      kept = keepNonzero(rows, ps, pt, pu, pv, g);
    }
    contraction_.accumulate(kept, ps, pt, pu, pv, g);
  }
  contraction_.end(result.coupling);

  result.raysCast = cast;
  result.raysBlocked = blocked;
  // Equal weights 1/N, applied once to the sum.
  scaleCoupling(link, 1.0 / double(count), result);
  result.kernelEvaluations = count;
}

}  // namespace radquad
