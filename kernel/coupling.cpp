#include "kernel/coupling.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstring>
#include <numbers>

#include "kernel/coupling_internal.h"
#include "kernel/legendre_basis.h"

namespace radquad {

using detail::kernelTimesPi;
using detail::placePoints;

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

}  // namespace radquad
