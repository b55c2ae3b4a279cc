#include "quadrature/rules/data_rule.h"

#include <cmath>
#include <string>
#include <vector>

#include "kernel/input_error.h"
#include "kernel/legendre_basis.h"

namespace radquad {
namespace {

void checkCoordinates(const std::vector<double>& values, const std::string& where,
                      const char* what) {
  for (std::size_t k = 0; k < values.size(); ++k) {
    if (!std::isfinite(values[k]) || values[k] < 0.0 || values[k] > 1.0) {
      throw InputError(where + ": " + what + "[" + std::to_string(k) + "] = " +
                       std::to_string(values[k]) + " is not in [0, 1]");
    }
  }
}

void checkWeights(const std::vector<double>& weights, const std::string& where,
                  const std::string& what) {
  const std::string label = what.empty() ? "weights" : what + " weights";
  if (weights.empty()) throw InputError(where + ": " + label + ": no points");
  double sum = 0.0, absolute = 0.0;
  for (std::size_t k = 0; k < weights.size(); ++k) {
    if (!std::isfinite(weights[k])) {
      throw InputError(where + ": " + label + "[" + std::to_string(k) + "] is not finite");
    }
    sum += weights[k];
    absolute += std::fabs(weights[k]);
  }
  if (std::fabs(sum - 1.0) > 1e-12 * std::max(1.0, absolute)) {
    throw InputError(where + ": " + label + " sum to " + std::to_string(sum) + ", not 1");
  }
}

}  // namespace

std::size_t DataRule::sampleCount() const {
  return spec_.product ? spec_.receiver.size() * spec_.source.size() : spec_.points.size();
}

RuleSamples DataRule::samples(std::uint64_t) const {
  RuleSamples out;
  out.isProduct = spec_.product;
  if (spec_.product) {
    out.receiver = spec_.receiver;
    out.source = spec_.source;
  } else {
    out.points = spec_.points;
  }
  return out;
}

double legendreExactnessError(const LinkSamples& points, int degree) {
  // phi_k at every point's four coordinates, k = 0..degree: 4 (degree + 1) values per point.
  const std::size_t n = points.size(), orders = std::size_t(degree) + 1;
  std::vector<double> values(4 * orders * n);
  const std::vector<double>* axes[4] = {&points.s, &points.t, &points.u, &points.v};
  for (std::size_t k = 0; k < n; ++k) {
    for (std::size_t axis = 0; axis < 4; ++axis) {
      shiftedLegendreValues(degree, (*axes[axis])[k], &values[(k * 4 + axis) * orders]);
    }
  }
  double worst = 0.0;
  for (int a = 0; a <= degree; ++a) {
    for (int b = 0; a + b <= degree; ++b) {
      for (int c = 0; a + b + c <= degree; ++c) {
        const int e = degree - a - b - c;
        double sum = 0.0;
        for (std::size_t k = 0; k < n; ++k) {
          const double* phi = &values[k * 4 * orders];
          sum += points.weight[k] * phi[std::size_t(a)] * phi[orders + std::size_t(b)] *
                 phi[2 * orders + std::size_t(c)] * phi[3 * orders + std::size_t(e)];
        }
        worst = std::max(worst, std::fabs(sum - (degree == 0 ? 1.0 : 0.0)));
      }
    }
  }
  return worst;
}

std::shared_ptr<const Rule> makeDataRule(DataRuleSpec spec, const std::string& where) {
  if (spec.name.empty()) throw InputError(where + ": the rule has no name");
  if (spec.product) {
    checkCoordinates(spec.receiver.u, where, "receiver.points u");
    checkCoordinates(spec.receiver.v, where, "receiver.points v");
    checkCoordinates(spec.source.u, where, "source.points u");
    checkCoordinates(spec.source.v, where, "source.points v");
    checkWeights(spec.receiver.weight, where, "receiver");
    checkWeights(spec.source.weight, where, "source");
  } else {
    checkCoordinates(spec.points.s, where, "points s");
    checkCoordinates(spec.points.t, where, "points t");
    checkCoordinates(spec.points.u, where, "points u");
    checkCoordinates(spec.points.v, where, "points v");
    checkWeights(spec.points.weight, where, "");
  }
  if (spec.degree) {
    if (*spec.degree < 0 || *spec.degree > kMaxDataRuleDegree) {
      throw InputError(where + ": degree " + std::to_string(*spec.degree) + " is not in [0, " +
                       std::to_string(kMaxDataRuleDegree) + "] (or null)");
    }
    RuleSamples samples;
    samples.isProduct = spec.product;
    samples.receiver = spec.receiver;
    samples.source = spec.source;
    samples.points = spec.points;
    const LinkSamples flat = flattenedPoints(samples);
    double absolute = 0.0;
    for (double w : flat.weight) absolute += std::fabs(w);
    for (int degree = 0; degree <= *spec.degree; ++degree) {
      const double error = legendreExactnessError(flat, degree);
      if (error > 1e-10 * absolute) {
        throw InputError(where + ": the rule is declared exact to degree " +
                         std::to_string(*spec.degree) + " but is not exact at degree " +
                         std::to_string(degree) + " (largest error over the tensor Legendre "
                         "polynomials " + std::to_string(error) + ")");
      }
    }
  }
  return std::shared_ptr<const Rule>(new DataRule(std::move(spec)));
}

}  // namespace radquad
