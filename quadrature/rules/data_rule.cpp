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

std::size_t DataRule::sampleCount() const { return spec_.draws.front().size(); }

RuleSamples DataRule::samples(std::uint64_t) const { return spec_.draws.front(); }

const RuleSamples& DataRule::listedDraw(std::size_t trial) const {
  if (!spec_.random || trial >= spec_.draws.size()) return Rule::listedDraw(trial);
  return spec_.draws[trial];
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

int exactnessDegree(const LinkSamples& points, int cap, double& failingError) {
  double absolute = 0.0;
  for (const double w : points.weight) absolute += std::fabs(w);
  for (int degree = 0; degree <= cap; ++degree) {
    const double error = legendreExactnessError(points, degree);
    if (error > 1e-10 * absolute) {
      failingError = error;
      return degree - 1;
    }
  }
  return cap;
}

std::shared_ptr<const Rule> makeDataRule(DataRuleSpec spec, const std::string& where) {
  if (spec.name.empty()) throw InputError(where + ": the rule has no name");
  if (spec.draws.empty()) throw InputError(where + ": the rule lists no draws");
  if (!spec.random && spec.draws.size() > 1) {
    throw InputError(where + ": a deterministic rule has one draw, not " +
                     std::to_string(spec.draws.size()));
  }
  if (spec.random && spec.degree) {
    throw InputError(where + ": a rule given as draws is random and declares no degree");
  }
  const RuleSamples& first = spec.draws.front();
  for (std::size_t d = 0; d < spec.draws.size(); ++d) {
    const RuleSamples& draw = spec.draws[d];
    const std::string at = spec.random ? where + ": draws[" + std::to_string(d) + "]" : where;
    if (draw.isProduct != first.isProduct || draw.size() != first.size() ||
        (draw.isProduct && draw.receiver.size() != first.receiver.size())) {
      throw InputError(at + ": every draw must have the form and the point counts of draw 0");
    }
    if (draw.isProduct) {
      checkCoordinates(draw.receiver.u, at, "receiver.points u");
      checkCoordinates(draw.receiver.v, at, "receiver.points v");
      checkCoordinates(draw.source.u, at, "source.points u");
      checkCoordinates(draw.source.v, at, "source.points v");
      checkWeights(draw.receiver.weight, at, "receiver");
      checkWeights(draw.source.weight, at, "source");
    } else {
      checkCoordinates(draw.points.s, at, "points s");
      checkCoordinates(draw.points.t, at, "points t");
      checkCoordinates(draw.points.u, at, "points u");
      checkCoordinates(draw.points.v, at, "points v");
      checkWeights(draw.points.weight, at, "");
    }
  }
  if (spec.degree) {
    if (*spec.degree < 0 || *spec.degree > kMaxDataRuleDegree) {
      throw InputError(where + ": degree " + std::to_string(*spec.degree) + " is not in [0, " +
                       std::to_string(kMaxDataRuleDegree) + "] (or null)");
    }
    double error = 0.0;
    const int exact = exactnessDegree(flattenedPoints(first), *spec.degree, error);
    if (exact < *spec.degree) {
      throw InputError(where + ": the rule is declared exact to degree " +
                       std::to_string(*spec.degree) + " but is not exact at degree " +
                       std::to_string(exact + 1) + " (largest error over the tensor Legendre "
                       "polynomials " + std::to_string(error) + ")");
    }
  }
  return std::shared_ptr<const Rule>(new DataRule(std::move(spec)));
}

}  // namespace radquad
