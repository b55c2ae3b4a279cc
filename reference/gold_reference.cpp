#include "reference/gold_reference.h"

#include <algorithm>
#include <cmath>
#include <memory>

#include "kernel/legendre_basis.h"
#include "quadrature/gauss_legendre.h"
#include "quadrature/prepared_rule.h"
#include "quadrature/rules/gauss_product.h"
#include "kernel/input_error.h"
#include "kernel/patch_intersection.h"
#include "reference/exact_gold.h"
#include "reference/exact_visibility.h"
#include "reference/point_polygon_form_factor.h"
#include "reference/stratified_reference.h"

namespace radquad {
namespace {

constexpr int kGaussOrders[] = {4, 8, 12, 16, 24, 32, 48};
// Seed indices of the dense draws, apart from the reference's replicates 0, 1, ...
constexpr std::uint32_t kDenseSeedIndex = 1u << 20;

double maxAbs(const Eigen::MatrixXd& matrix) {
  return matrix.cwiseAbs().maxCoeff();
}

// The Gauss sequence of a link without occluders (no rays are cast).
void gaussGold(const Link& link, int degree, double tolerance, GoldReference& gold) {
  LinkIntegral previous;
  // One accumulator per thread for every link's sequence: its buffers grow to the largest
  // order once (48^4 kernel values) instead of being allocated, faulted in and zeroed again
  // for every link. Nothing in the sequence waits on other tasks, so a thread never enters
  // it twice at once.
  thread_local CouplingAccumulator accumulator;
  bool havePrevious = false;
  for (int n : kGaussOrders) {
    const PreparedRule prepared(std::make_shared<GaussProductRule>(GaussPointCounts{n, n, n, n}), degree);
    LinkIntegral current;
    prepared.integrate(link, 0, accumulator, current);
    gold.kernelEvaluations += current.kernelEvaluations;
    if (havePrevious) {
      gold.coupling = current.coupling;
      gold.formFactor = current.formFactor;
      gold.couplingError = (current.coupling - previous.coupling).cwiseAbs();
      gold.formFactorError = std::fabs(current.formFactor - previous.formFactor);
      gold.gaussPoints = n;
      gold.converged = maxAbs(gold.couplingError) <= tolerance * maxAbs(current.coupling);
      if (gold.converged) return;
    }
    previous = current;
    havePrevious = true;
  }
}

Eigen::VectorXd lambertColumnAtOrder(const Link& link, int degree, int n) {
  const GaussLegendreRule& rule = gaussLegendreUnit(n);
  const int functions = basisFunctionCount(degree);
  Eigen::VectorXd column = Eigen::VectorXd::Zero(functions);
  double values[basisFunctionCount(kMaxBasisDegree)];
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      const double s = rule.nodes[i], t = rule.nodes[j];
      const double inner =
          pointToPatchFormFactor(link.receiver.pointAt(s, t), link.receiver.normal, link.source);
      tensorBasisValues(degree, s, t, values);
      const double w = rule.weights[i] * rule.weights[j] * inner;
      for (int a = 0; a < functions; ++a) column[a] += w * values[a];
    }
  }
  // K[a][0] = int M_a(x) F(x) / sqrt(A_s) dA = sqrt(A_r / A_s) int phi_a F ds dt.
  return column * std::sqrt(link.receiver.area / link.source.area);
}

}  // namespace

bool singularLink(const Link& link) {
  const double size = std::max({link.receiver.edgeU.norm(), link.receiver.edgeV.norm(),
                                link.source.edgeU.norm(), link.source.edgeV.norm()});
  return patchDistance(link.receiver, link.source) <= 1e-9 * size ||
         cutByTangentPlane(link.receiver, link.source);
}

const char* goldMethodName(GoldMethod method) {
  switch (method) {
    case GoldMethod::automatic: return "auto";
    case GoldMethod::exact: return "exact";
    case GoldMethod::stratified: return "stratified";
  }
  return "?";
}

GoldMethod parseGoldMethod(const std::string& name, const std::string& what) {
  if (name == "auto") return GoldMethod::automatic;
  if (name == "exact") return GoldMethod::exact;
  if (name == "stratified") return GoldMethod::stratified;
  throw InputError(what + ": unknown gold method '" + name + "' (auto, exact or stratified)");
}

LambertCheck lambertColumn(const Link& link, int degree, double tolerance) {
  LambertCheck check;
  Eigen::VectorXd previous;
  for (int n : {4, 8, 16, 32, 64}) {
    Eigen::VectorXd current = lambertColumnAtOrder(link, degree, n);
    if (previous.size() > 0) {
      check.column = current;
      check.outerPoints = n;
      check.error = (current - previous).cwiseAbs().maxCoeff();
      check.converged = check.error <= tolerance * current.cwiseAbs().maxCoeff();
      if (check.converged) break;
    }
    previous = std::move(current);
  }
  return check;
}

GoldReference goldReference(const Link& link, int degree, std::uint64_t seed,
                            const GoldOptions& options) {
  validateBasisDegree(degree);
  GoldReference gold;
  // Which gold a link takes is decided by its geometry, never by sample rays: a ray that
  // misses a thin shadow would take the link for unoccluded and give it an error of 0.
  const ExactVisibility visibility(link);
  const bool shadowed = visibility.occludersInShaft() > 0;
  GoldMethod method = options.method;
  if (method == GoldMethod::automatic) {
    // No occluder meets the shaft and the kernel is smooth over the link: the Gauss sequence,
    // its visibility 1 everywhere, with no rays. Where the kernel is not smooth even without
    // occluders (touching patches, one crossing the other's plane), the sequence converges
    // algebraically: up to 48^4 points it does not reach the tolerance, so such links, and
    // shadowed ones, take the exact gold, or the dense gold where their shafts hold more than
    // maxExactOccluders polygons.
    if (!shadowed && !singularLink(link)) {
      gaussGold(Link{link.receiver, link.source, nullptr}, degree, options.tolerance, gold);
      if (gold.converged) {
        gold.method = "gauss product";
        LambertCheck check = lambertColumn(link, degree, options.tolerance);
        check.maxDifference = (check.column - gold.coupling.col(0)).cwiseAbs().maxCoeff();
        gold.lambert = std::move(check);
        return gold;
      }
    }
    method = visibility.candidateCount() <= options.maxExactOccluders ? GoldMethod::exact
                                                                      : GoldMethod::stratified;
  }
  const std::uint64_t gaussEvaluations = gold.kernelEvaluations;
  if (method == GoldMethod::exact) {
    ExactGoldOptions exactOptions;
    exactOptions.tolerance = options.exactTolerance;
    exactOptions.maxEvaluations = options.maxEvaluations;
    exactOptions.progress = options.progress;
    const ExactGold exact = exactGold(link, degree, exactOptions);
    gold = GoldReference{};
    gold.kernelEvaluations = gaussEvaluations;
    gold.method = "exact visibility";
    gold.coupling = exact.coupling;
    gold.couplingError = exact.couplingError;
    gold.formFactor = exact.formFactor;
    gold.formFactorError = exact.formFactorError;
    gold.converged = exact.converged;
    gold.confirmed = exact.confirmed;
    gold.receiverPoints = exact.receiverPoints;
    gold.shaftOccluders = exact.candidateOccluders;
    gold.outerMethod = exactOuterMethodName(exact.outer);
    gold.criticalSegments = exact.criticalSegments;
    gold.unoccludedApart = exact.unoccludedApart;
    return gold;
  }
  gold = GoldReference{};
  gold.method = "dense stratified";
  const ReplicateMean mean = stratifiedReplicateMean(link, degree, seed, options.denseStrata,
                                                     options.denseReplicates, kDenseSeedIndex);
  gold.coupling = mean.coupling;
  gold.formFactor = mean.formFactor;
  gold.couplingError = mean.couplingStandardError;
  gold.formFactorError = mean.formFactorStandardError;
  gold.converged = true;
  gold.kernelEvaluations = gaussEvaluations + mean.kernelEvaluations;
  return gold;
}

}  // namespace radquad
