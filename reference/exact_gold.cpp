#include "reference/exact_gold.h"

#include <cubature.h>

#include <cmath>
#include <vector>

#include "kernel/input_error.h"
#include "kernel/legendre_basis.h"
#include "reference/exact_visibility.h"
#include "reference/source_moments.h"

namespace radquad {
namespace {

struct OuterIntegrand {
  const Link& link;
  int degree;
  int functions;
  double scale;  // sqrt(A_r / A_s)
  ExactVisibility visibility;
  SourceMoments moments;
  VisibleRings rings;
  std::vector<double> inner;
  std::vector<double> receiverValues;
  std::uint64_t points = 0;
  bool finite = true;

  OuterIntegrand(const Link& l, int d)
      : link(l),
        degree(d),
        functions(basisFunctionCount(d)),
        scale(std::sqrt(l.receiver.area / l.source.area)),
        visibility(l),
        moments(l.source, d),
        inner(std::size_t(basisFunctionCount(d))),
        receiverValues(std::size_t(basisFunctionCount(d))) {}

  void evaluate(double s, double t, double* out) {
    ++points;
    const Eigen::Vector3d x = link.receiver.pointAt(s, t);
    visibility.visibleRings(x, rings);
    moments.compute(x, link.receiver.normal, rings, inner.data());
    tensorBasisValues(degree, s, t, receiverValues.data());
    for (int a = 0; a < functions; ++a) {
      const double weight = scale * receiverValues[a];
      for (int b = 0; b < functions; ++b) out[a * functions + b] = weight * inner[b];
    }
    for (int b = 0; b < functions; ++b) finite = finite && std::isfinite(inner[b]);
  }
};

int integrandCallback(unsigned /*dimensions*/, std::size_t count, const double* points, void* data,
                      unsigned values, double* out) {
  auto* integrand = static_cast<OuterIntegrand*>(data);
  for (std::size_t k = 0; k < count; ++k) {
    integrand->evaluate(points[2 * k], points[2 * k + 1], out + k * values);
  }
  return integrand->finite ? 0 : 1;
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
  if (!integrand.finite) {
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
  gold.polygonUnions = integrand.visibility.statistics().unions;
  gold.candidateOccluders = integrand.visibility.candidateCount();
  return gold;
}

}  // namespace radquad
