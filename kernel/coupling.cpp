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
  // Restrict-qualified locals: the stores cannot alias the inputs, so the loop vectorises.
  double* __restrict px = x.data();
  double* __restrict py = y.data();
  double* __restrict pz = z.data();
  double* __restrict own = ownNormalDot.data();
  double* __restrict other = otherNormalDot.data();
  const double* __restrict pu = u;
  const double* __restrict pv = v;
  const double ox = o.x(), oy = o.y(), oz = o.z(), ax = a.x(), ay = a.y(), az = a.z();
  const double bx = b.x(), by = b.y(), bz = b.z(), nx = n.x(), ny = n.y(), nz = n.z();
  const double mx = otherNormal.x(), my = otherNormal.y(), mz = otherNormal.z();
  for (std::size_t k = 0; k < count; ++k) {
    const double xk = ox + pu[k] * ax + pv[k] * bx;
    const double yk = oy + pu[k] * ay + pv[k] * by;
    const double zk = oz + pu[k] * az + pv[k] * bz;
    px[k] = xk;
    py[k] = yk;
    pz[k] = zk;
    own[k] = nx * xk + ny * yk + nz * zk;
    other[k] = mx * xk + my * yk + mz * zk;
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
    // The one-dimensional values are computed across the block's points (vectorised), then
    // the tensor products column by column (column-major: a column is contiguous in k).
    constexpr std::size_t kBlock = 256;
    const int n1 = degree + 1;
    receiverBlock_.resize(kBlock, functions);
    sourceBlock_.resize(kBlock, functions);
    legendre_.resize(4 * std::size_t(n1) * kBlock);
    weightedKernel_.resize(kBlock);
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
