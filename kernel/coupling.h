// The coupling matrix of a link (docs/design.md, "Conventions"):
//   K[a][b] = int_{A_r} int_{A_s} M_a(x) G(x,x') M_b(x') dA' dA,
//   G(x,x') = cos(theta) cos(theta') V(x,x') / (pi |x - x'|^2),
// estimated as A_r A_s sum_k w_k M_a(x_k) G(x_k,x'_k) M_b(x'_k) from one set of kernel
// evaluations shared by all (d+1)^4 basis pairs. With unit-square basis values phi,
// M = phi / sqrt(A), so K = sqrt(A_r A_s) sum_k w_k phi_a(x_k) G_k phi_b(x'_k).
//
// Both cosines are clamped at zero, which for the unoccluded kernel gives the
// square-root-free form G = max(0, n_r.d) max(0, -n_s.d) / (pi |d|^4), d = x' - x.
// Visibility rays are cast only where that product is positive.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "kernel/block_contraction.h"
#include "kernel/occluder_scene.h"
#include "kernel/patch.h"
#include "kernel/sample_points.h"

namespace radquad {

// Energy flows from `source` to `receiver`; `occluders` may be null (nothing in the way).
struct Link {
  Patch receiver;
  Patch source;
  const OccluderScene* occluders = nullptr;

  bool hasOccluders() const { return occluders != nullptr && !occluders->empty(); }
};

// What integrating one link yields.
struct LinkIntegral {
  Eigen::MatrixXd coupling;  // rows: receiver functions a, columns: source functions b
  double formFactor = 0.0;   // (1/A_r) int int G dA' dA = K[0][0] sqrt(A_s/A_r)
  std::uint64_t kernelEvaluations = 0;
  std::uint64_t raysCast = 0;  // one per evaluation whose unoccluded kernel is positive
  std::uint64_t raysBlocked = 0;

  // The fraction of cast rays that were not blocked (1 when none was cast).
  double visibleFraction() const {
    return raysCast == 0 ? 1.0 : 1.0 - double(raysBlocked) / double(raysCast);
  }
};

// Weighted unit-square basis values of one side of a product rule:
// values[k * functions + a] = weight_k * phi_a(u_k, v_k). Build once per (rule, degree).
struct WeightedBasisTable {
  int degree = 0;
  int functions = 1;
  std::vector<double> values;

  std::size_t points() const { return values.size() / std::size_t(functions); }
};

WeightedBasisTable makeWeightedBasisTable(const PatchSamples& samples, int degree);

// The unoccluded kernel (with the 1/pi) at one pair of points; exposed for tests and for
// the analytic references.
double unoccludedKernel(const Patch& receiver, const Eigen::Vector3d& x, const Patch& source,
                        const Eigen::Vector3d& y);

// Reusable scratch space: one per thread, so the hot loops allocate nothing once warm.
class CouplingAccumulator {
 public:
  // Product rule: the kernel is evaluated on every (receiver point, source point) pair.
  void product(const Link& link, const PatchSamples& receiver,
               const WeightedBasisTable& receiverBasis, const PatchSamples& source,
               const WeightedBasisTable& sourceBasis, LinkIntegral& result);

  // A general 4D point set.
  void scattered(const Link& link, const LinkSamples& samples, int degree, LinkIntegral& result);

  // A 4D point set of equal weights produced block by block (the large random rules): the
  // same sum as scattered() on the same points, fused per block of 256 points (draw, place,
  // kernel, rays, contraction) so nothing of the 10,000 points goes through memory.
  void streamed(const Link& link, const PointStream& points, int degree, LinkIntegral& result);

 private:
  // The "place" step of every path: the receiver's points (ru, rv)[0..nr) and the source's
  // (su, sv)[0..ns) in 3D, with the cosines each side needs, into the placed-point columns.
  void placeLink(const Link& link, const double* ru, const double* rv, std::size_t nr,
                 const double* su, const double* sv, std::size_t ns);
  // The "contract" step's last factor: the accumulated sums, times weightScale (the points'
  // common weight, 1 when the weights were applied), become K and the form factor.
  static void scaleCoupling(const Link& link, double weightScale, LinkIntegral& result);
  // Traces segments_ (segment r belongs to kernel value rayPairs_[r]) and zeroes the kernel
  // where they are blocked.
  void castRays(const Link& link, std::vector<double>& kernel, LinkIntegral& result);
  // Sizes the staging columns for `count` rays; traceStagedRays traces them (ray k belongs to
  // kernel value k) and zeroes the kernel where they are blocked.
  void stageRays(std::size_t count);
  void traceStagedRays(const Link& link, std::size_t count, LinkIntegral& result);

  std::vector<double> receiverX_, receiverY_, receiverZ_, receiverNormalDot_, receiverSourceDot_;
  std::vector<double> sourceX_, sourceY_, sourceZ_, sourceNormalDot_, sourceReceiverDot_;
  std::vector<double> kernel_;
  std::vector<double> partial_;
  std::vector<std::uint32_t> rayPairs_;
  std::vector<float> rayOriginX_, rayOriginY_, rayOriginZ_;
  std::vector<float> rayDirectionX_, rayDirectionY_, rayDirectionZ_;
  SegmentBatch segments_;
  std::vector<double> weightedKernel_;
  std::vector<double> streamBlock_;  // streamed(): the block's columns
  detail::BlockContraction contraction_;
};

}  // namespace radquad
