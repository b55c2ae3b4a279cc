#include "kernel/coupling.h"
#include "kernel/input_error.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <numbers>

#include "kernel/coupling_internal.h"
#include "kernel/legendre_basis.h"
#include "kernel/product_contraction.h"

namespace radquad {

using detail::kContract;
using detail::kContractSourceLast;
using detail::kernelTimesPi;
using detail::kLanes;
using detail::Lanes8;
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
  // Whole packets: SegmentBatch::assignColumns copies 16 lanes at a time.
  const std::size_t lanes = (count + 15) / 16 * 16;
  for (auto* column : {&rayOriginX_, &rayOriginY_, &rayOriginZ_, &rayDirectionX_, &rayDirectionY_,
                       &rayDirectionZ_}) {
    column->resize(lanes);
  }
}

void CouplingAccumulator::traceStagedRays(const Link& link, std::size_t count,
                                          LinkIntegral& result) {
  segments_.assignColumns(count, rayOriginX_.data(), rayOriginY_.data(), rayOriginZ_.data(),
                          rayDirectionX_.data(), rayDirectionY_.data(), rayDirectionZ_.data());
  result.raysCast = count;
  result.raysBlocked = link.occluders->traceMasking(segments_, kernel_.data());
}

void CouplingAccumulator::castRays(const Link& link, std::vector<double>& kernel,
                                   LinkIntegral& result) {
  result.raysCast = segments_.size();
  result.raysBlocked = link.occluders->traceMasking(segments_, rayPairs_.data(), kernel.data());
}

namespace {

// Columns of placed points, receiver or source side (placePoints).
struct PlacedPoints {
  const double* x;
  const double* y;
  const double* z;
  const double* ownNormalDot;
  const double* otherNormalDot;
};

// Columns of float rays, ray k = i ns + j from receiver point i to source point j.
struct StagedRays {
  float* originX;
  float* originY;
  float* originZ;
  float* directionX;
  float* directionY;
  float* directionZ;
};

using simd::Floats8;

inline Lanes8 load8(const double* p) {
  Lanes8 v;
  std::memcpy(&v, p, sizeof v);
  return v;
}

// kernelTimesPi (coupling_internal.h) on eight pairs: the same operations in the same order.
inline Lanes8 kernelTimesPi8(Lanes8 dx, Lanes8 dy, Lanes8 dz, Lanes8 receiverCos,
                             Lanes8 sourceCos) {
  const Lanes8 zero = {};
  const Lanes8 r2 = dx * dx + dy * dy + dz * dz;
  const Lanes8 c =
      (receiverCos < zero ? zero : receiverCos) * (sourceCos < zero ? zero : sourceCos);
  return c > zero ? c / (r2 * r2) : zero;
}

// One receiver point's row: row[j] = pi G(x, x'_j) without visibility, eight source points at a
// time. With Rays, also the rays of the row's pairs: from (x, y, z) along x'_j - x, both
// rounded to float from doubles.
template <bool Rays>
inline void kernelRow(std::size_t ns, double x, double y, double z, double receiverOwn,
                      double receiverSource, const PlacedPoints& source, double* __restrict row,
                      const StagedRays& rays, std::size_t first) {
  const float fx = float(x), fy = float(y), fz = float(z);
  std::size_t j = 0;
  for (; j + kLanes <= ns; j += kLanes) {
    const Lanes8 dx = load8(source.x + j) - x;
    const Lanes8 dy = load8(source.y + j) - y;
    const Lanes8 dz = load8(source.z + j) - z;
    const Lanes8 g = kernelTimesPi8(dx, dy, dz, load8(source.otherNormalDot + j) - receiverOwn,
                                    receiverSource - load8(source.ownNormalDot + j));
    std::memcpy(row + j, &g, sizeof g);
    if constexpr (Rays) {
      const std::size_t k = first + j;
      // Broadcasts as fx - 0, which is fx even for -0 (0 + fx would give +0).
      const Floats8 ox = fx - Floats8{}, oy = fy - Floats8{}, oz = fz - Floats8{};
      const Floats8 ex = __builtin_convertvector(dx, Floats8);
      const Floats8 ey = __builtin_convertvector(dy, Floats8);
      const Floats8 ez = __builtin_convertvector(dz, Floats8);
      std::memcpy(rays.originX + k, &ox, sizeof ox);
      std::memcpy(rays.originY + k, &oy, sizeof oy);
      std::memcpy(rays.originZ + k, &oz, sizeof oz);
      std::memcpy(rays.directionX + k, &ex, sizeof ex);
      std::memcpy(rays.directionY + k, &ey, sizeof ey);
      std::memcpy(rays.directionZ + k, &ez, sizeof ez);
    }
  }
  for (; j < ns; ++j) {
    const double dx = source.x[j] - x, dy = source.y[j] - y, dz = source.z[j] - z;
    row[j] = kernelTimesPi(dx, dy, dz, source.otherNormalDot[j] - receiverOwn,
                           receiverSource - source.ownNormalDot[j]);
    if constexpr (Rays) {
      const std::size_t k = first + j;
      rays.originX[k] = fx;
      rays.originY[k] = fy;
      rays.originZ[k] = fz;
      rays.directionX[k] = float(dx);
      rays.directionY[k] = float(dy);
      rays.directionZ[k] = float(dz);
    }
  }
}

// kernel[i * ns + j] = pi G(x_i, x'_j) without visibility, with the ray of pair k = i ns + j
// when `rays` is given.
void evaluateKernel(const PlacedPoints& r, std::size_t nr, const PlacedPoints& s, std::size_t ns,
                    double* kernel, const StagedRays* rays) {
  for (std::size_t i = 0; i < nr; ++i) {
    const std::size_t k = i * ns;
    if (rays) {
      kernelRow<true>(ns, r.x[i], r.y[i], r.z[i], r.ownNormalDot[i], r.otherNormalDot[i], s,
                      kernel + k, *rays, k);
    } else {
      kernelRow<false>(ns, r.x[i], r.y[i], r.z[i], r.ownNormalDot[i], r.otherNormalDot[i], s,
                       kernel + k, {}, k);
    }
  }
}

}  // namespace

void CouplingAccumulator::scaleCoupling(const Link& link, double weightScale,
                                        LinkIntegral& result) {
  const double receiverArea = link.receiver.area, sourceArea = link.source.area;
  result.coupling *= weightScale * std::sqrt(receiverArea * sourceArea) / std::numbers::pi;
  result.formFactor = result.coupling(0, 0) * std::sqrt(sourceArea / receiverArea);
}

void CouplingAccumulator::placeLink(const Link& link, const double* ru, const double* rv,
                                    std::size_t nr, const double* su, const double* sv,
                                    std::size_t ns) {
  placePoints(link.receiver, ru, rv, nr, link.source.normal, receiverX_, receiverY_, receiverZ_,
              receiverNormalDot_, receiverSourceDot_);
  placePoints(link.source, su, sv, ns, link.receiver.normal, sourceX_, sourceY_, sourceZ_,
              sourceNormalDot_, sourceReceiverDot_);
}

void CouplingAccumulator::product(const Link& link, const PatchSamples& receiver,
                                  const WeightedBasisTable& receiverBasis,
                                  const PatchSamples& source, const WeightedBasisTable& sourceBasis,
                                  LinkIntegral& result) {
  RADQUAD_REQUIRE(receiverBasis.degree == sourceBasis.degree);
  RADQUAD_REQUIRE(receiverBasis.points() == receiver.size() && sourceBasis.points() == source.size());
  const std::size_t nr = receiver.size();
  const std::size_t ns = source.size();
  placeLink(link, receiver.u.data(), receiver.v.data(), nr, source.u.data(), source.v.data(), ns);

  const std::size_t pairs = nr * ns;
  kernel_.resize(pairs);
  const PlacedPoints receiverPoints{receiverX_.data(), receiverY_.data(), receiverZ_.data(),
                                    receiverNormalDot_.data(), receiverSourceDot_.data()};
  const PlacedPoints sourcePoints{sourceX_.data(), sourceY_.data(), sourceZ_.data(),
                                  sourceNormalDot_.data(), sourceReceiverDot_.data()};
  result.raysCast = 0;
  result.raysBlocked = 0;
  if (!link.hasOccluders()) {
    evaluateKernel(receiverPoints, nr, sourcePoints, ns, kernel_.data(), nullptr);
  } else {
    stageRays(pairs);
    const StagedRays staged{rayOriginX_.data(),    rayOriginY_.data(),    rayOriginZ_.data(),
                            rayDirectionX_.data(), rayDirectionY_.data(), rayDirectionZ_.data()};
    evaluateKernel(receiverPoints, nr, sourcePoints, ns, kernel_.data(), &staged);
    std::size_t positive = 0;
    for (std::size_t k = 0; k < pairs; ++k) positive += detail::needsRay(kernel_[k]) ? 1 : 0;
    if (positive == pairs) {
      // Every pair faces the other (the usual case): one ray per pair in pair order, staged
      // with the kernel and applied without branches.
      traceStagedRays(link, pairs, result);
    } else {
      segments_.resize(positive);
      rayPairs_.resize(positive);
      std::size_t rays = 0;
      for (std::size_t i = 0; i < nr; ++i) {
        for (std::size_t j = 0; j < ns; ++j) {
          if (!detail::needsRay(kernel_[i * ns + j])) continue;
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
  scaleCoupling(link, 1.0, result);
  result.kernelEvaluations = nr * ns;
}

}  // namespace radquad
