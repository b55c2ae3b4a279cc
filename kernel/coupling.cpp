#include "kernel/coupling.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <numbers>

#include "kernel/legendre_basis.h"

namespace radquad {
namespace {

// Positions and normal projections of a patch's sample points, structure-of-arrays.
void placePoints(const Patch& patch, const double* u, const double* v, std::size_t count,
                 const Eigen::Vector3d& otherNormal, std::vector<double>& x, std::vector<double>& y,
                 std::vector<double>& z, std::vector<double>& ownNormalDot,
                 std::vector<double>& otherNormalDot) {
  x.resize(count);
  y.resize(count);
  z.resize(count);
  ownNormalDot.resize(count);
  otherNormalDot.resize(count);
  const Eigen::Vector3d& o = patch.origin;
  const Eigen::Vector3d& a = patch.edgeU;
  const Eigen::Vector3d& b = patch.edgeV;
  const Eigen::Vector3d& n = patch.normal;
  for (std::size_t k = 0; k < count; ++k) {
    x[k] = o.x() + u[k] * a.x() + v[k] * b.x();
    y[k] = o.y() + u[k] * a.y() + v[k] * b.y();
    z[k] = o.z() + u[k] * a.z() + v[k] * b.z();
    ownNormalDot[k] = n.x() * x[k] + n.y() * y[k] + n.z() * z[k];
    otherNormalDot[k] = otherNormal.x() * x[k] + otherNormal.y() * y[k] + otherNormal.z() * z[k];
  }
}

// cos(theta) cos(theta') |d|^2 / |d|^4 with d = y - x:
// n_r.d = n_r.y - n_r.x and -n_s.d = n_s.x - n_s.y.
inline double kernelTimesPi(double dx, double dy, double dz, double receiverCos,
                            double sourceCos) {
  const double r2 = dx * dx + dy * dy + dz * dz;
  const double c = std::max(receiverCos, 0.0) * std::max(sourceCos, 0.0);
  return c / (r2 * r2);
}

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

void CouplingAccumulator::castRays(const Link& link, std::vector<double>& kernel,
                                   LinkIntegral& result) {
  rayVisible_.resize(segments_.size());
  link.occluders->testSegments(segments_, rayVisible_.data());
  std::uint64_t blocked = 0;
  for (std::size_t r = 0; r < rayPairs_.size(); ++r) {
    if (!rayVisible_[r]) {
      kernel[rayPairs_[r]] = 0.0;
      ++blocked;
    }
  }
  result.raysCast = rayPairs_.size();
  result.raysBlocked = blocked;
}

void CouplingAccumulator::product(const Link& link, const PatchSamples& receiver,
                                  const WeightedBasisTable& receiverBasis,
                                  const PatchSamples& source,
                                  const WeightedBasisTable& sourceBasis, LinkIntegral& result) {
  assert(receiverBasis.functions == sourceBasis.functions);
  assert(receiverBasis.points() == receiver.size() && sourceBasis.points() == source.size());
  const std::size_t nr = receiver.size();
  const std::size_t ns = source.size();
  const std::size_t functions = std::size_t(receiverBasis.functions);
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
    segments_.clear();
    rayPairs_.clear();
    for (std::size_t i = 0; i < nr; ++i) {
      for (std::size_t j = 0; j < ns; ++j) {
        if (kernel_[i * ns + j] <= 0.0) continue;
        const Eigen::Vector3d from(receiverX_[i], receiverY_[i], receiverZ_[i]);
        const Eigen::Vector3d to(sourceX_[j], sourceY_[j], sourceZ_[j]);
        segments_.push(from, to - from);
        rayPairs_.push_back(std::uint32_t(i * ns + j));
      }
    }
    castRays(link, kernel_, result);
  }

  // partial = kernel (nr x ns) * sourceBasis (ns x functions), then
  // coupling = receiverBasis^T (functions x nr) * partial.
  partial_.assign(nr * functions, 0.0);
  for (std::size_t i = 0; i < nr; ++i) {
    double* __restrict out = partial_.data() + i * functions;
    const double* __restrict row = kernel_.data() + i * ns;
    for (std::size_t j = 0; j < ns; ++j) {
      const double g = row[j];
      const double* __restrict basis = sourceBasis.values.data() + j * functions;
      for (std::size_t b = 0; b < functions; ++b) out[b] += g * basis[b];
    }
  }
  result.coupling.setZero(Eigen::Index(functions), Eigen::Index(functions));
  double* __restrict coupling = result.coupling.data();  // column-major: (a, b) at b*F + a
  for (std::size_t i = 0; i < nr; ++i) {
    const double* __restrict basis = receiverBasis.values.data() + i * functions;
    const double* __restrict partialRow = partial_.data() + i * functions;
    for (std::size_t b = 0; b < functions; ++b) {
      const double p = partialRow[b];
      double* __restrict column = coupling + b * functions;
      for (std::size_t a = 0; a < functions; ++a) column[a] += basis[a] * p;
    }
  }
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
  placePoints(s, samples.u.data(), samples.v.data(), count, r.normal, sourceX_, sourceY_,
              sourceZ_, sourceNormalDot_, sourceReceiverDot_);
  kernel_.resize(count);
  for (std::size_t k = 0; k < count; ++k) {
    kernel_[k] = kernelTimesPi(sourceX_[k] - receiverX_[k], sourceY_[k] - receiverY_[k],
                               sourceZ_[k] - receiverZ_[k],
                               sourceReceiverDot_[k] - receiverNormalDot_[k],
                               receiverSourceDot_[k] - sourceNormalDot_[k]);
  }
  result.raysCast = 0;
  result.raysBlocked = 0;
  if (link.hasOccluders()) {
    segments_.clear();
    rayPairs_.clear();
    for (std::size_t k = 0; k < count; ++k) {
      if (kernel_[k] <= 0.0) continue;
      const Eigen::Vector3d from(receiverX_[k], receiverY_[k], receiverZ_[k]);
      const Eigen::Vector3d to(sourceX_[k], sourceY_[k], sourceZ_[k]);
      segments_.push(from, to - from);
      rayPairs_.push_back(std::uint32_t(k));
    }
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
    constexpr std::size_t kBlock = 512;
    receiverBlock_.resize(kBlock, functions);
    sourceBlock_.resize(kBlock, functions);
    double values[basisFunctionCount(kMaxBasisDegree)];
    for (std::size_t start = 0; start < count; start += kBlock) {
      const std::size_t rows = std::min(kBlock, count - start);
      for (std::size_t row = 0; row < rows; ++row) {
        const std::size_t k = start + row;
        const double scale = samples.weight[k] * kernel_[k];
        tensorBasisValues(degree, samples.s[k], samples.t[k], values);
        for (int a = 0; a < functions; ++a) receiverBlock_(Eigen::Index(row), a) = scale * values[a];
        tensorBasisValues(degree, samples.u[k], samples.v[k], values);
        for (int b = 0; b < functions; ++b) sourceBlock_(Eigen::Index(row), b) = values[b];
      }
      const auto n = Eigen::Index(rows);
      result.coupling.noalias() +=
          receiverBlock_.topRows(n).transpose() * sourceBlock_.topRows(n);
    }
  }
  result.coupling *= std::sqrt(r.area * s.area) / std::numbers::pi;
  result.formFactor = result.coupling(0, 0) * std::sqrt(s.area / r.area);
  result.kernelEvaluations = count;
}

}  // namespace radquad
