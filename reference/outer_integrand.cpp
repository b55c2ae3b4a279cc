#include "reference/outer_integrand.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "quadrature/gauss_legendre.h"
#include "reference/adaptive_pieces.h"

namespace radquad::exact_gold_detail {

void evaluateBatch(OuterIntegrand& integrand, std::size_t count, const double* points, double* out) {
  const std::size_t values = std::size_t(integrand.functions * integrand.functions);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, count, 8),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      Worker& worker = integrand.workers.local();
                      for (std::size_t k = range.begin(); k < range.end(); ++k) {
                        integrand.evaluate(worker, points[2 * k], points[2 * k + 1],
                                           out + k * values);
                      }
                    });
  integrand.points += count;
  integrand.report(integrand.points);
}

std::vector<double> gaussProduct(OuterIntegrand& integrand, int n) {
  const GaussLegendreRule& rule = gaussLegendreUnit(n);
  const std::size_t values = std::size_t(integrand.functions * integrand.functions);
  const std::size_t count = std::size_t(n) * std::size_t(n);
  std::vector<double> points(2 * count);
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      points[2 * std::size_t(i * n + j)] = rule.nodes[std::size_t(i)];
      points[2 * std::size_t(i * n + j) + 1] = rule.nodes[std::size_t(j)];
    }
  }
  std::vector<double> out(count * values);
  evaluateBatch(integrand, count, points.data(), out.data());
  std::vector<double> sum(values, 0.0);
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      const double w = rule.weights[std::size_t(i)] * rule.weights[std::size_t(j)];
      const double* f = out.data() + std::size_t(i * n + j) * values;
      for (std::size_t v = 0; v < values; ++v) sum[v] += w * f[v];
    }
  }
  return sum;
}

double largestOfSum(const std::vector<double>& known, const std::vector<double>& value) {
  if (known.empty()) return largestAbs(value);
  double largest = 0.0;
  for (std::size_t v = 0; v < value.size(); ++v) {
    largest = std::max(largest, std::abs(known[v] + value[v]));
  }
  return largest;
}
}  // namespace radquad::exact_gold_detail
