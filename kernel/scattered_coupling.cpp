// The scattered coupling path: a general list of 4D points, evaluated in blocks of 256 so the
// basis values stay in cache (DESIGN.md, "Mathematical conventions"; kernel/coupling.h).
#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstring>
#include <numbers>

#include "kernel/coupling.h"
#include "kernel/coupling_internal.h"
#include "kernel/legendre_basis.h"

namespace radquad {
namespace {

using detail::kernelTimesPi;
using detail::placePoints;

// phi_k at `count` points, k = 0..degree, written out[k * stride + r]: Bonnet's recurrence
// (k+1) P_{k+1}(y) = (2k+1) y P_k(y) - k P_{k-1}(y), y = 2x - 1, then phi_k = sqrt(2k+1) P_k,
// as shiftedLegendreValues, but across points so that it vectorises.
void legendreAcrossPoints(int degree, const double* __restrict x, std::size_t count,
                          std::size_t stride, double* __restrict out) {
  for (std::size_t r = 0; r < count; ++r) out[r] = 1.0;
  if (degree >= 1) {
    for (std::size_t r = 0; r < count; ++r) out[stride + r] = 2.0 * x[r] - 1.0;
  }
  for (int k = 1; k < degree; ++k) {
    const double a = 2.0 * k + 1.0, c = double(k), d = k + 1.0;
    const double* __restrict previous = out + std::size_t(k - 1) * stride;
    const double* __restrict current = out + std::size_t(k) * stride;
    double* __restrict next = out + std::size_t(k + 1) * stride;
    for (std::size_t r = 0; r < count; ++r) {
      next[r] = (a * (2.0 * x[r] - 1.0) * current[r] - c * previous[r]) / d;
    }
  }
  for (int k = 1; k <= degree; ++k) {
    const double scale = std::sqrt(2.0 * k + 1.0);
    double* __restrict row = out + std::size_t(k) * stride;
    for (std::size_t r = 0; r < count; ++r) row[r] *= scale;
  }
}

// coupling (column-major F x F) += sum over the block's points p of
//   wg_p phi_i(s_p) phi_j(t_p) * phi_k(u_p) phi_l(v_p),  a = i*N1 + j, b = k*N1 + l,
// for N1 = d + 1 known at compile time. The source products are formed once per block; each
// receiver function's values are formed on the fly and multiplied into F accumulators of 8
// lanes each, which stay in registers (F <= 16). `rows` is a multiple of 8; padded rows carry
// zeros.
template <int N1>
void contractScatteredBlock(std::size_t rows, std::size_t stride, const double* __restrict wg,
                            const double* __restrict alongS, const double* __restrict alongT,
                            const double* __restrict alongU, const double* __restrict alongV,
                            double* __restrict sourceProducts, double* __restrict coupling) {
  constexpr int F = N1 * N1;
  for (int k = 0; k < N1; ++k) {
    for (int l = 0; l < N1; ++l) {
      const double* __restrict lu = alongU + std::size_t(k) * stride;
      const double* __restrict lv = alongV + std::size_t(l) * stride;
      double* __restrict column = sourceProducts + std::size_t(k * N1 + l) * stride;
      for (std::size_t p = 0; p < rows; ++p) column[p] = lu[p] * lv[p];
    }
  }
  // Eight-lane vectors (GCC/Clang vector extension), so the F accumulators are registers.
  typedef double Lanes __attribute__((vector_size(64)));
  auto load = [](const double* from) {
    Lanes lanes;
    std::memcpy(&lanes, from, sizeof(lanes));
    return lanes;
  };
  for (int i = 0; i < N1; ++i) {
    for (int j = 0; j < N1; ++j) {
      const double* __restrict ls = alongS + std::size_t(i) * stride;
      const double* __restrict lt = alongT + std::size_t(j) * stride;
      Lanes accumulators[F];
      for (int b = 0; b < F; ++b) accumulators[b] = Lanes{};
      for (std::size_t p = 0; p < rows; p += 8) {
        const Lanes receiver = load(wg + p) * load(ls + p) * load(lt + p);
#pragma GCC unroll 16
        for (int b = 0; b < F; ++b) {
          accumulators[b] += receiver * load(sourceProducts + std::size_t(b) * stride + p);
        }
      }
      const int a = i * N1 + j;
      for (int b = 0; b < F; ++b) {
        double sum = 0.0;
        for (int lane = 0; lane < 8; ++lane) sum += accumulators[b][lane];
        coupling[std::size_t(b) * F + a] += sum;
      }
    }
  }
}

using ScatteredContractFunction = void (*)(std::size_t, std::size_t, const double*, const double*,
                                           const double*, const double*, const double*, double*,
                                           double*);

// Indexed by basis degree 1..3; higher degrees use a general matrix product.
constexpr ScatteredContractFunction kScatteredContract[4] = {
    nullptr, contractScatteredBlock<2>, contractScatteredBlock<3>, contractScatteredBlock<4>};

}  // namespace

void CouplingAccumulator::scattered(const Link& link, const LinkSamples& samples, int degree,
                                    LinkIntegral& result) {
  validateBasisDegree(degree);
  const std::size_t count = samples.size();
  const Patch& r = link.receiver;
  const Patch& s = link.source;
  placePoints(r, samples.s.data(), samples.t.data(), count, s.normal, receiverX_, receiverY_,
              receiverZ_, receiverNormalDot_, receiverSourceDot_);
  placePoints(s, samples.u.data(), samples.v.data(), count, r.normal, sourceX_, sourceY_, sourceZ_,
              sourceNormalDot_, sourceReceiverDot_);
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
    for (std::size_t k = 0; k < count; ++k) positive += kernel_[k] > 0.0 ? 1 : 0;
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
      if (kernel_[k] <= 0.0) continue;
      segments_.set(rays, receiverX_[k], receiverY_[k], receiverZ_[k], sourceX_[k] - receiverX_[k],
                    sourceY_[k] - receiverY_[k], sourceZ_[k] - receiverZ_[k]);
      rayPairs_[rays++] = std::uint32_t(k);
    }
    segments_.resize(rays);
    rayPairs_.resize(rays);
    castRays(link, kernel_, result);
  }

  const int functions = basisFunctionCount(degree);
  result.coupling.setZero(functions, functions);
  if (degree == 0) {
    double sum = 0.0;
    for (std::size_t k = 0; k < count; ++k) sum += samples.weight[k] * kernel_[k];
    result.coupling(0, 0) = sum;
  } else {
    // Blocks keep the basis tables in cache: coupling += receiverBlock^T sourceBlock with
    // receiverBlock(k, a) = w_k G_k phi_a(s_k, t_k) and sourceBlock(k, b) = phi_b(u_k, v_k).
    // The one-dimensional values are computed across the block's points (vectorised), then
    // the tensor products column by column (column-major: a column is contiguous in k).
    constexpr std::size_t kBlock = 256;
    const int n1 = degree + 1;
    if (degree > 3) {
      receiverBlock_.resize(kBlock, functions);
      sourceBlock_.resize(kBlock, functions);
    }
    legendre_.resize(4 * std::size_t(n1) * kBlock);
    weightedKernel_.resize(kBlock);
    sourceProducts_.resize(std::size_t(functions) * kBlock);
    double* alongS = legendre_.data();
    double* alongT = alongS + std::size_t(n1) * kBlock;
    double* alongU = alongT + std::size_t(n1) * kBlock;
    double* alongV = alongU + std::size_t(n1) * kBlock;
    for (std::size_t start = 0; start < count; start += kBlock) {
      const std::size_t rows = std::min(kBlock, count - start);
      legendreAcrossPoints(degree, samples.s.data() + start, rows, kBlock, alongS);
      legendreAcrossPoints(degree, samples.t.data() + start, rows, kBlock, alongT);
      legendreAcrossPoints(degree, samples.u.data() + start, rows, kBlock, alongU);
      legendreAcrossPoints(degree, samples.v.data() + start, rows, kBlock, alongV);
      {
        const double* __restrict w = samples.weight.data() + start;
        const double* __restrict g = kernel_.data() + start;
        double* __restrict wg = weightedKernel_.data();
        for (std::size_t row = 0; row < rows; ++row) wg[row] = w[row] * g[row];
      }
      if (degree <= 3) {
        // Pad to whole vectors of 8 with zero weights and zero basis values.
        const std::size_t padded = (rows + 7) / 8 * 8;
        for (std::size_t row = rows; row < padded; ++row) {
          weightedKernel_[row] = 0.0;
          for (int k = 0; k < n1; ++k) {
            for (double* along : {alongS, alongT, alongU, alongV})
              along[std::size_t(k) * kBlock + row] = 0.0;
          }
        }
        kScatteredContract[degree](padded, kBlock, weightedKernel_.data(), alongS, alongT, alongU,
                                   alongV, sourceProducts_.data(), result.coupling.data());
        continue;
      }
      for (int i = 0; i < n1; ++i) {
        for (int j = 0; j < n1; ++j) {
          const int a = i * n1 + j;
          const double* __restrict ls = alongS + std::size_t(i) * kBlock;
          const double* __restrict lt = alongT + std::size_t(j) * kBlock;
          const double* __restrict lu = alongU + std::size_t(i) * kBlock;
          const double* __restrict lv = alongV + std::size_t(j) * kBlock;
          const double* __restrict wg = weightedKernel_.data();
          double* __restrict receiverColumn = receiverBlock_.col(a).data();
          double* __restrict sourceColumn = sourceBlock_.col(a).data();
          for (std::size_t row = 0; row < rows; ++row) {
            receiverColumn[row] = wg[row] * (ls[row] * lt[row]);
            sourceColumn[row] = lu[row] * lv[row];
          }
        }
      }
      const auto n = Eigen::Index(rows);
      result.coupling.noalias() += receiverBlock_.topRows(n).transpose() * sourceBlock_.topRows(n);
    }
  }
  result.coupling *= std::sqrt(r.area * s.area) / std::numbers::pi;
  result.formFactor = result.coupling(0, 0) * std::sqrt(s.area / r.area);
  result.kernelEvaluations = count;
}

}  // namespace radquad
