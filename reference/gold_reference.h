// Gold references: much more accurate than the paper's reference, to measure how far the
// paper's 10,000-sample reference itself, and every rule, is off (docs/design.md, "The gold").
//
// Which gold a link takes (GoldOptions::method):
// - auto (the default), decided by the link's geometry, never by sample rays:
//   - no occluder meets the link's shaft (ExactVisibility::occludersInShaft) and the kernel
//     is smooth over it: the Gauss-Legendre product with n points on every axis for n = 4, 8,
//     12, 16, 24, 32, 48, until two successive orders agree to `tolerance` times the largest
//     |K| entry; the error reported is the entrywise difference of the last two orders (a
//     bound on the coarser one, so conservative for the finer one returned). No rays are
//     cast: no segment between the patches is blocked;
//   - an occluder meets the shaft, or the kernel is not smooth (touching patches, a source
//     crossing the receiver's plane), or the Gauss sequence does not converge: the
//     exact-visibility gold (exact_gold.h), deterministic, to `exactTolerance` of the largest
//     |K| entry, when the link's shaft holds at most `maxExactOccluders` occluder polygons;
//     otherwise the dense stratified gold (below);
// - exact: the exact-visibility gold on every link, whatever its occluders;
// - stratified: on every link the mean of `denseReplicates` independent draws of
//   Stratified:k with k = `denseStrata` (default 16 x 24^4 = 5.3 million samples) with the
//   standard error of that mean.
// - Constant source functions on links taking the Gauss gold: an independent check of column
//   b = 0, K[a][0] = sqrt(A_r/A_s) int_{[0,1]^2} phi_a(s,t) F(x(s,t) -> source) ds dt, with
//   the inner integral by Lambert's contour formula (point_polygon_form_factor.h) and the
//   outer one by Gauss products of rising order.
//
// Options (GoldOptions):
// | field             | default | meaning                                                  |
// |-------------------|---------|----------------------------------------------------------|
// | method            | auto    | auto (by geometry), exact or stratified on every link    |
// | tolerance         | 1e-9    | agreement of two Gauss orders, relative to max |K|       |
// | exactTolerance    | 1e-7    | estimated error of the exact gold, relative to max |K|   |
// | maxEvaluations    | 2000000 | receiver points of the exact gold (then not converged)   |
// | maxExactOccluders | 64      | auto: more occluder polygons in the shaft, dense gold    |
// | denseStrata       | 24      | k of the dense Stratified:k                              |
// | denseReplicates   | 16      | independent dense draws averaged                         |
#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>

#include "kernel/coupling.h"

namespace radquad {

enum class GoldMethod { automatic, exact, stratified };

const char* goldMethodName(GoldMethod method);
// "auto", "exact" or "stratified"; throws InputError naming `what` otherwise.
GoldMethod parseGoldMethod(const std::string& name, const std::string& what);

struct GoldOptions {
  GoldMethod method = GoldMethod::automatic;
  double tolerance = 1e-9;
  double exactTolerance = 1e-7;
  std::size_t maxEvaluations = 2000000;
  std::size_t maxExactOccluders = 64;
  int denseStrata = 24;
  int denseReplicates = 16;
  // Exact visibility: progress reports (ExactGoldOptions::progress); may be empty.
  std::function<void(std::uint64_t points, double seconds)> progress;
};

struct LambertCheck {
  Eigen::VectorXd column;      // K[a][0] from the contour formula
  double maxDifference = 0.0;  // max_a |column[a] - gold K[a][0]|
  double error = 0.0;          // difference of the last two outer Gauss orders
  int outerPoints = 0;         // per axis on the receiver
  bool converged = false;
};

struct GoldReference {
  std::string method;  // "gauss product", "exact visibility" or "dense stratified"
  Eigen::MatrixXd coupling;
  double formFactor = 0.0;
  // Gauss: |K_n - K_previous| entrywise; exact visibility: the cubature's error estimate;
  // dense stratified: the standard error of the mean.
  Eigen::MatrixXd couplingError;
  double formFactorError = 0.0;
  // Gauss orders agreed, or the exact gold met its tolerance with its estimate confirmed
  // (always true for dense stratified, whose error is statistical).
  bool converged = false;
  bool confirmed = true;  // exact visibility: ExactGold::confirmed
  int gaussPoints = 0;  // per axis, Gauss only
  // Kernel evaluations spent: the Gauss sequence's (also when the link then went to another
  // method) and the dense draws'; the exact gold's inner integrals are not evaluations.
  std::uint64_t kernelEvaluations = 0;
  std::uint64_t receiverPoints = 0;     // exact visibility: inner integrals taken
  std::size_t shaftOccluders = 0;       // exact visibility: occluder polygons in the shaft
  // exact visibility: "critical lines", "jump lines" or "genz-malik"
  std::string outerMethod;
  std::size_t criticalSegments = 0;     // exact visibility: segments on the receiver
  bool unoccludedApart = false;         // exact visibility: K_free integrated apart
  std::optional<LambertCheck> lambert;
};

GoldReference goldReference(const Link& link, int degree, std::uint64_t seed,
                            const GoldOptions& options = {});

// Whether the kernel is not smooth over the link, occluders aside: its patches touch (a wall
// on a floor: singular along the contact) or one crosses the other's plane (the clamped cosine
// is discontinuous there). Product rules do not resolve such links (the solver integrates them
// with composite rules); the study scores them as a class of their own.
bool singularLink(const Link& link);

// The Lambert check alone (unoccluded links; ignores occluders).
LambertCheck lambertColumn(const Link& link, int degree, double tolerance);

}  // namespace radquad
