#include "quadrature/gauss_legendre.h"

#include <array>
#include <cmath>
#include <mutex>
#include <numbers>
#include <string>

#include "kernel/input_error.h"

namespace radquad {
namespace {

void validatePointCount(int n) {
  if (n < 1 || n > kMaxGaussPoints) {
    throw InputError("Gauss-Legendre point count " + std::to_string(n) +
                     " is out of range: expected 1.." + std::to_string(kMaxGaussPoints));
  }
}

// P_n(x) and P_n'(x) by Bonnet's recurrence.
void legendreAndDerivative(int n, long double x, long double& value, long double& derivative) {
  long double previous = 1.0L;
  long double current = x;
  for (int k = 1; k < n; ++k) {
    const long double next = ((2.0L * k + 1.0L) * x * current - k * previous) / (k + 1.0L);
    previous = current;
    current = next;
  }
  value = n == 0 ? 1.0L : current;
  derivative = n * (x * current - previous) / (x * x - 1.0L);
}

}  // namespace

GaussLegendreRule gaussLegendre(int n) {
  validatePointCount(n);
  GaussLegendreRule rule;
  rule.nodes.resize(n);
  rule.weights.resize(n);
  if (n == 1) {
    rule.nodes[0] = 0.0;
    rule.weights[0] = 2.0;
    return rule;
  }
  const long double pi = std::numbers::pi_v<long double>;
  for (int i = 0; i < (n + 1) / 2; ++i) {
    // Tricomi's initial guess for the i-th largest zero, then Newton.
    long double x = std::cos(pi * (i + 0.75L) / (n + 0.5L));
    long double value = 0.0L, derivative = 1.0L;
    for (int iteration = 0; iteration < 100; ++iteration) {
      legendreAndDerivative(n, x, value, derivative);
      const long double step = value / derivative;
      x -= step;
      if (std::fabs(step) < 1e-19L) break;
    }
    legendreAndDerivative(n, x, value, derivative);
    const long double weight = 2.0L / ((1.0L - x * x) * derivative * derivative);
    // Symmetric pair: the i-th largest and the i-th smallest.
    rule.nodes[n - 1 - i] = double(x);
    rule.nodes[i] = double(-x);
    rule.weights[n - 1 - i] = double(weight);
    rule.weights[i] = double(weight);
  }
  if (n % 2 == 1) rule.nodes[n / 2] = 0.0;
  return rule;
}

const GaussLegendreRule& gaussLegendreUnit(int n) {
  validatePointCount(n);
  static std::array<GaussLegendreRule, kMaxGaussPoints + 1> cache;
  static std::array<std::once_flag, kMaxGaussPoints + 1> computed;
  std::call_once(computed[n], [n] {
    GaussLegendreRule rule = gaussLegendre(n);
    for (int i = 0; i < n; ++i) {
      rule.nodes[i] = 0.5 * (1.0 + rule.nodes[i]);
      rule.weights[i] *= 0.5;
    }
    cache[n] = std::move(rule);
  });
  return cache[n];
}

PatchSamples gaussProductSamples(int alongU, int alongV) {
  const GaussLegendreRule& ruleU = gaussLegendreUnit(alongU);
  const GaussLegendreRule& ruleV = gaussLegendreUnit(alongV);
  PatchSamples samples;
  for (int i = 0; i < alongU; ++i) {
    for (int j = 0; j < alongV; ++j) {
      samples.push(ruleU.nodes[std::size_t(i)], ruleV.nodes[std::size_t(j)],
                   ruleU.weights[std::size_t(i)] * ruleV.weights[std::size_t(j)]);
    }
  }
  return samples;
}

}  // namespace radquad
