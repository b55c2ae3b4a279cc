#include "kernel/coupling.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstring>
#include <numbers>

#include "kernel/legendre_basis.h"

namespace radquad {
namespace {

// Positions and normal projections of a patch's sample points, structure-of-arrays.
void placePoints(const Patch& patch, const double* __restrict u, const double* __restrict v,
                 std::size_t count, const Eigen::Vector3d& otherNormal, std::vector<double>& xs,
                 std::vector<double>& ys, std::vector<double>& zs,
                 std::vector<double>& ownNormalDots, std::vector<double>& otherNormalDots) {
  for (auto* column : {&xs, &ys, &zs, &ownNormalDots, &otherNormalDots}) column->resize(count);
  double* __restrict x = xs.data();
  double* __restrict y = ys.data();
  double* __restrict z = zs.data();
  double* __restrict ownNormalDot = ownNormalDots.data();
  double* __restrict otherNormalDot = otherNormalDots.data();
  const double ox = patch.origin.x(), oy = patch.origin.y(), oz = patch.origin.z();
  const double ax = patch.edgeU.x(), ay = patch.edgeU.y(), az = patch.edgeU.z();
  const double bx = patch.edgeV.x(), by = patch.edgeV.y(), bz = patch.edgeV.z();
  const double nx = patch.normal.x(), ny = patch.normal.y(), nz = patch.normal.z();
  const double mx = otherNormal.x(), my = otherNormal.y(), mz = otherNormal.z();
  for (std::size_t k = 0; k < count; ++k) {
    x[k] = ox + u[k] * ax + v[k] * bx;
    y[k] = oy + u[k] * ay + v[k] * by;
    z[k] = oz + u[k] * az + v[k] * bz;
    ownNormalDot[k] = nx * x[k] + ny * y[k] + nz * z[k];
    otherNormalDot[k] = mx * x[k] + my * y[k] + mz * z[k];
  }
}

// cos(theta) cos(theta') |d|^2 / |d|^4 with d = y - x:
// n_r.d = n_r.y - n_r.x and -n_s.d = n_s.x - n_s.y.
inline double kernelTimesPi(double dx, double dy, double dz, double receiverCos, double sourceCos) {
  const double r2 = dx * dx + dy * dy + dz * dz;
  const double c = std::max(receiverCos, 0.0) * std::max(sourceCos, 0.0);
  return c / (r2 * r2);
}

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

WeightedBasisTable makeWeightedBasisTable(const PatchSamples& samples, int degree) {
  validateBasisDegree(degree);
  WeightedBasisTable table;
  table.degree = degree;
  table.functions = basisFunctionCount(degree);
  table.values.resize(samples.size() * std::size_t(table.functions));
  for (std::size_t k = 0; k < samples.size(); ++k) {
    double* row = table.values.data() + k * std::size_t(table.functions);
    tensorBasisValues(degree, samples.u[k], samples.v[k], row);
    for (int a = 0; a < table.functions; ++a) row[a] *= samples.weight[k];
  }
  return table;
}

double unoccludedKernel(const Patch& receiver, const Eigen::Vector3d& x, const Patch& source,
                        const Eigen::Vector3d& y) {
  const Eigen::Vector3d d = y - x;
  return kernelTimesPi(d.x(), d.y(), d.z(), receiver.normal.dot(d), -source.normal.dot(d)) /
         std::numbers::pi;
}

void CouplingAccumulator::stageRays(std::size_t count) {
  for (auto* column : {&rayOriginX_, &rayOriginY_, &rayOriginZ_, &rayDirectionX_, &rayDirectionY_,
                       &rayDirectionZ_, &rayFar_}) {
    column->resize(count);
  }
}

void CouplingAccumulator::traceStagedRays(const Link& link, std::size_t count,
                                          LinkIntegral& result) {
  segments_.assign(count, rayOriginX_.data(), rayOriginY_.data(), rayOriginZ_.data(),
                   rayDirectionX_.data(), rayDirectionY_.data(), rayDirectionZ_.data());
  link.occluders->trace(segments_);
  segments_.farEnds(rayFar_.data());
  std::uint64_t blocked = 0;
  const float* __restrict far = rayFar_.data();
  double* __restrict kernel = kernel_.data();
  for (std::size_t k = 0; k < count; ++k) {
    const bool visible = far[k] >= 0.0f;
    kernel[k] = visible ? kernel[k] : 0.0;
    blocked += visible ? 0 : 1;
  }
  result.raysCast = count;
  result.raysBlocked = blocked;
}

void CouplingAccumulator::castRays(const Link& link, std::vector<double>& kernel,
                                   LinkIntegral& result) {
  link.occluders->trace(segments_);
  std::uint64_t blocked = 0;
  for (std::size_t r = 0; r < rayPairs_.size(); ++r) {
    if (!segments_.visible(r)) {
      kernel[rayPairs_[r]] = 0.0;
      ++blocked;
    }
  }
  result.raysCast = rayPairs_.size();
  result.raysBlocked = blocked;
}

namespace {

// coupling (column-major F x F) = receiverBasis^T (nr x F) * (kernel (nr x ns) * sourceBasis
// (ns x F)), with F known at compile time so the inner loops unroll into full vectors. Both
// stages accumulate in registers: first each receiver point's row of the partial product,
// then each column of the coupling.
template <int F>
void contractProduct(std::size_t nr, std::size_t ns, const double* __restrict kernel,
                     const double* __restrict receiverBasis, const double* __restrict sourceBasis,
                     double* __restrict partial, double* __restrict coupling) {
  for (std::size_t i = 0; i < nr; ++i) {
    double row[F] = {};
    const double* __restrict g = kernel + i * ns;
    for (std::size_t j = 0; j < ns; ++j) {
      const double* __restrict basis = sourceBasis + j * F;
      for (int b = 0; b < F; ++b) row[b] += g[j] * basis[b];
    }
    for (int b = 0; b < F; ++b) partial[i * F + b] = row[b];
  }
  for (int b = 0; b < F; ++b) {
    double column[F] = {};
    for (std::size_t i = 0; i < nr; ++i) {
      const double p = partial[i * F + b];
      const double* __restrict basis = receiverBasis + i * F;
      for (int a = 0; a < F; ++a) column[a] += basis[a] * p;
    }
    for (int a = 0; a < F; ++a) coupling[b * F + a] = column[a];
  }
}

// The same product in the other order, coupling = (receiverBasis^T kernel) sourceBasis:
// F nr ns + F ns F multiplications instead of nr ns F + F nr F, fewer when the source has
// fewer points than the receiver (the adaptive rules of Gershbein 1995, section 5).
// partial (F x ns, column j = sum_i kernel[i][j] receiverBasis[i]).
template <int F>
void contractProductSourceLast(std::size_t nr, std::size_t ns, const double* __restrict kernel,
                               const double* __restrict receiverBasis,
                               const double* __restrict sourceBasis, double* __restrict partial,
                               double* __restrict coupling) {
  for (std::size_t j = 0; j < ns; ++j) {
    double column[F] = {};
    for (std::size_t i = 0; i < nr; ++i) {
      const double g = kernel[i * ns + j];
      const double* __restrict basis = receiverBasis + i * F;
      for (int a = 0; a < F; ++a) column[a] += basis[a] * g;
    }
    for (int a = 0; a < F; ++a) partial[j * F + a] = column[a];
  }
  for (int b = 0; b < F; ++b) {
    double column[F] = {};
    for (std::size_t j = 0; j < ns; ++j) {
      const double weight = sourceBasis[j * F + b];
      const double* __restrict p = partial + j * F;
      for (int a = 0; a < F; ++a) column[a] += p[a] * weight;
    }
    for (int a = 0; a < F; ++a) coupling[b * F + a] = column[a];
  }
}

using ContractFunction = void (*)(std::size_t, std::size_t, const double*, const double*,
                                  const double*, double*, double*);

// Indexed by basis degree d = 0..kMaxBasisDegree, F = (d+1)^2.
constexpr ContractFunction kContract[kMaxBasisDegree + 1] = {
    contractProduct<1>,  contractProduct<4>,  contractProduct<9>,
    contractProduct<16>, contractProduct<25>, contractProduct<36>,
    contractProduct<49>, contractProduct<64>, contractProduct<81>};
constexpr ContractFunction kContractSourceLast[kMaxBasisDegree + 1] = {
    contractProductSourceLast<1>,  contractProductSourceLast<4>,  contractProductSourceLast<9>,
    contractProductSourceLast<16>, contractProductSourceLast<25>, contractProductSourceLast<36>,
    contractProductSourceLast<49>, contractProductSourceLast<64>, contractProductSourceLast<81>};

}  // namespace

void CouplingAccumulator::product(const Link& link, const PatchSamples& receiver,
                                  const WeightedBasisTable& receiverBasis,
                                  const PatchSamples& source, const WeightedBasisTable& sourceBasis,
                                  LinkIntegral& result) {
  assert(receiverBasis.degree == sourceBasis.degree);
  assert(receiverBasis.points() == receiver.size() && sourceBasis.points() == source.size());
  const std::size_t nr = receiver.size();
  const std::size_t ns = source.size();
  const Patch& r = link.receiver;
  const Patch& s = link.source;
  placePoints(r, receiver.u.data(), receiver.v.data(), nr, s.normal, receiverX_, receiverY_,
              receiverZ_, receiverNormalDot_, receiverSourceDot_);
  placePoints(s, source.u.data(), source.v.data(), ns, r.normal, sourceX_, sourceY_, sourceZ_,
              sourceNormalDot_, sourceReceiverDot_);

  kernel_.resize(nr * ns);
  {
    const double* __restrict sx = sourceX_.data();
    const double* __restrict sy = sourceY_.data();
    const double* __restrict sz = sourceZ_.data();
    const double* __restrict sOwn = sourceNormalDot_.data();
    const double* __restrict sRec = sourceReceiverDot_.data();
    for (std::size_t i = 0; i < nr; ++i) {
      const double xi = receiverX_[i], yi = receiverY_[i], zi = receiverZ_[i];
      const double receiverOwn = receiverNormalDot_[i];
      const double receiverSrc = receiverSourceDot_[i];
      double* __restrict row = kernel_.data() + i * ns;
      for (std::size_t j = 0; j < ns; ++j) {
        row[j] = kernelTimesPi(sx[j] - xi, sy[j] - yi, sz[j] - zi, sRec[j] - receiverOwn,
                               receiverSrc - sOwn[j]);
      }
    }
  }

  result.raysCast = 0;
  result.raysBlocked = 0;
  if (link.hasOccluders()) {
    const std::size_t pairs = nr * ns;
    std::size_t positive = 0;
    for (std::size_t k = 0; k < pairs; ++k) positive += kernel_[k] > 0.0 ? 1 : 0;
    if (positive == pairs) {
      // Every pair faces the other (the usual case): one ray per pair in pair order, filled
      // and applied without branches.
      stageRays(pairs);
      for (std::size_t i = 0; i < nr; ++i) {
        const double xi = receiverX_[i], yi = receiverY_[i], zi = receiverZ_[i];
        float* __restrict ox = rayOriginX_.data() + i * ns;
        float* __restrict oy = rayOriginY_.data() + i * ns;
        float* __restrict oz = rayOriginZ_.data() + i * ns;
        float* __restrict dx = rayDirectionX_.data() + i * ns;
        float* __restrict dy = rayDirectionY_.data() + i * ns;
        float* __restrict dz = rayDirectionZ_.data() + i * ns;
        for (std::size_t j = 0; j < ns; ++j) {
          ox[j] = float(xi);
          oy[j] = float(yi);
          oz[j] = float(zi);
          dx[j] = float(sourceX_[j] - xi);
          dy[j] = float(sourceY_[j] - yi);
          dz[j] = float(sourceZ_[j] - zi);
        }
      }
      traceStagedRays(link, pairs, result);
    } else {
      segments_.resize(positive);
      rayPairs_.resize(positive);
      std::size_t rays = 0;
      for (std::size_t i = 0; i < nr; ++i) {
        for (std::size_t j = 0; j < ns; ++j) {
          if (kernel_[i * ns + j] <= 0.0) continue;
          segments_.set(rays, receiverX_[i], receiverY_[i], receiverZ_[i],
                        sourceX_[j] - receiverX_[i], sourceY_[j] - receiverY_[i],
                        sourceZ_[j] - receiverZ_[i]);
          rayPairs_[rays++] = std::uint32_t(i * ns + j);
        }
      }
      castRays(link, kernel_, result);
    }
  }

  const int degree = receiverBasis.degree;
  const int functions = basisFunctionCount(degree);
  result.coupling.resize(functions, functions);
  partial_.resize(std::max(nr, ns) * std::size_t(functions));
  (ns < nr ? kContractSourceLast : kContract)[degree](
      nr, ns, kernel_.data(), receiverBasis.values.data(), sourceBasis.values.data(),
      partial_.data(), result.coupling.data());
  result.coupling *= std::sqrt(r.area * s.area) / std::numbers::pi;
  result.formFactor = result.coupling(0, 0) * std::sqrt(s.area / r.area);
  result.kernelEvaluations = nr * ns;
}

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
