#include "reference/exact_gold.h"

#include <cubature.h>
#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <cmath>
#include <vector>

#include "kernel/input_error.h"
#include "kernel/legendre_basis.h"
#include "reference/exact_visibility.h"
#include "reference/source_moments.h"

namespace radquad {
namespace {

// One thread's scratch: visibility and inner integrals are computed per point.
struct Worker {
  ExactVisibility visibility;
  SourceMoments moments;
  VisibleRings rings;
  std::vector<double> inner;
  std::vector<double> receiverValues;
  bool finite = true;

  Worker(const Link& link, int degree)
      : visibility(link),
        moments(link.source, degree),
        inner(std::size_t(basisFunctionCount(degree))),
        receiverValues(std::size_t(basisFunctionCount(degree))) {}
};

struct OuterIntegrand {
  const Link& link;
  int degree;
  int functions;
  double scale;  // sqrt(A_r / A_s)
  tbb::enumerable_thread_specific<Worker> workers;
  std::uint64_t points = 0;

  OuterIntegrand(const Link& l, int d)
      : link(l),
        degree(d),
        functions(basisFunctionCount(d)),
        scale(std::sqrt(l.receiver.area / l.source.area)),
        workers([&l, d] { return Worker(l, d); }) {}

  void evaluate(Worker& worker, double s, double t, double* out) const {
    const Eigen::Vector3d x = link.receiver.pointAt(s, t);
    worker.visibility.visibleRings(x, worker.rings);
    worker.moments.compute(x, link.receiver.normal, worker.rings, worker.inner.data());
    tensorBasisValues(degree, s, t, worker.receiverValues.data());
    for (int a = 0; a < functions; ++a) {
      const double weight = scale * worker.receiverValues[a];
      for (int b = 0; b < functions; ++b) out[a * functions + b] = weight * worker.inner[b];
    }
    for (int b = 0; b < functions; ++b) worker.finite = worker.finite && std::isfinite(worker.inner[b]);
  }

  bool finite() {
    bool all = true;
    for (const Worker& worker : workers) all = all && worker.finite;
    return all;
  }
};

// Points are independent: a batch is spread over threads, and the values do not depend on
// which thread computed them.
int integrandCallback(unsigned /*dimensions*/, std::size_t count, const double* points, void* data,
                      unsigned values, double* out) {
  auto* integrand = static_cast<OuterIntegrand*>(data);
  integrand->points += count;
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, count, 8),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      Worker& worker = integrand->workers.local();
                      for (std::size_t k = range.begin(); k < range.end(); ++k) {
                        integrand->evaluate(worker, points[2 * k], points[2 * k + 1],
                                            out + k * values);
                      }
                    });
  return integrand->finite() ? 0 : 1;
}

}  // namespace

ExactGold exactGold(const Link& link, int degree, const ExactGoldOptions& options) {
  validateBasisDegree(degree);
  if (!(options.tolerance > 0.0)) throw InputError("exact gold: tolerance must be positive");
  OuterIntegrand integrand(link, degree);
  const unsigned values = unsigned(integrand.functions * integrand.functions);
  std::vector<double> value(values), error(values);
  const double low[2] = {0.0, 0.0}, high[2] = {1.0, 1.0};
  const int status =
      hcubature_v(values, integrandCallback, &integrand, 2, low, high, options.maxEvaluations, 0.0,
                  options.tolerance, ERROR_LINF, value.data(), error.data());
  if (!integrand.finite()) {
    throw ComputationError("exact gold: the inner integral was not finite");
  }
  if (status != 0) throw ComputationError("exact gold: the cubature failed");
  ExactGold gold;
  const int n = integrand.functions;
  gold.coupling.resize(n, n);
  gold.couplingError.resize(n, n);
  for (int a = 0; a < n; ++a) {
    for (int b = 0; b < n; ++b) {
      gold.coupling(a, b) = value[std::size_t(a * n + b)];
      gold.couplingError(a, b) = error[std::size_t(a * n + b)];
    }
  }
  const double toFormFactor = std::sqrt(link.source.area / link.receiver.area);
  gold.formFactor = gold.coupling(0, 0) * toFormFactor;
  gold.formFactorError = gold.couplingError(0, 0) * toFormFactor;
  const double largest = gold.coupling.cwiseAbs().maxCoeff();
  gold.converged = gold.couplingError.maxCoeff() <= options.tolerance * largest;
  gold.receiverPoints = integrand.points;
  // Every worker culled the same shaft: read the count from one instead of culling again.
  for (const Worker& worker : integrand.workers) {
    gold.polygonUnions += worker.visibility.statistics().unions;
    gold.candidateOccluders = worker.visibility.candidateCount();
  }
  return gold;
}

}  // namespace radquad
