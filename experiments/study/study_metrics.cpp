#include "experiments/study/study_metrics.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "kernel/legendre_basis.h"

namespace radquad {

double relativeError(const Eigen::MatrixXd& estimate, const Eigen::MatrixXd& reference) {
  return std::abs(estimate(0, 0) - reference(0, 0)) / reference(0, 0);
}

std::vector<double> l1ErrorBound(const Eigen::MatrixXd& difference, double receiverArea) {
  const int functions = int(difference.rows());
  const int side = int(std::lround(std::sqrt(double(functions))));
  // c_k computed once: legendreAbsoluteIntegral integrates numerically, and the study asks
  // for it for every link, rule and trial.
  static const std::array<double, kMaxBasisDegree + 1> absoluteIntegral = [] {
    std::array<double, kMaxBasisDegree + 1> values{};
    for (int k = 0; k <= kMaxBasisDegree; ++k) values[std::size_t(k)] = legendreAbsoluteIntegral(k);
    return values;
  }();
  // (1/A_r) sqrt(A_r) = 1/sqrt(A_r).
  const double perUnitArea = 1.0 / std::sqrt(receiverArea);
  std::vector<double> bound(std::size_t(functions), 0.0);
  for (int b = 0; b < functions; ++b) {
    double sum = 0.0;
    for (int a = 0; a < functions; ++a) {
      const int i = a / side, j = a % side;
      sum += std::abs(difference(a, b)) * absoluteIntegral[std::size_t(i)] *
             absoluteIntegral[std::size_t(j)];
    }
    bound[std::size_t(b)] = sum * perUnitArea;
  }
  return bound;
}

double relativeFrobeniusError(const Eigen::MatrixXd& estimate, const Eigen::MatrixXd& reference) {
  return (estimate - reference).norm() / reference.norm();
}

PairedRatio pairedRatio(const std::vector<double>& numerator,
                        const std::vector<double>& denominator) {
  const std::size_t n = std::min(numerator.size(), denominator.size());
  PairedRatio out;
  if (n == 0) return out;
  double sumA = 0.0, sumB = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    sumA += numerator[i];
    sumB += denominator[i];
  }
  out.ratio = sumA / sumB;
  out.low = out.high = out.ratio;
  if (n < 2) return out;
  const double meanB = sumB / double(n);
  double squares = 0.0;  // z has mean 0 by construction of the ratio
  for (std::size_t i = 0; i < n; ++i) {
    const double z = (numerator[i] - out.ratio * denominator[i]) / meanB;
    squares += z * z;
  }
  const double relative = std::sqrt(squares / double(n - 1) / double(n)) / out.ratio;
  out.low = out.ratio * std::exp(-1.96 * relative);
  out.high = out.ratio * std::exp(1.96 * relative);
  return out;
}

PairedRatio unpairedRatio(const std::vector<double>& numerator,
                          const std::vector<double>& denominator) {
  const SummaryStatistics a = summarize(numerator), b = summarize(denominator);
  PairedRatio out;
  out.ratio = a.mean / b.mean;
  const double relative =
      std::sqrt(a.sem * a.sem / (a.mean * a.mean) + b.sem * b.sem / (b.mean * b.mean));
  out.low = out.ratio * std::exp(-1.96 * relative);
  out.high = out.ratio * std::exp(1.96 * relative);
  return out;
}

SummaryStatistics summarize(std::vector<double> values) {
  SummaryStatistics out;
  out.count = values.size();
  if (values.empty()) return out;
  std::sort(values.begin(), values.end());
  const auto quantile = [&](double q) {
    const double position = q * double(values.size() - 1);
    const std::size_t low = std::size_t(std::floor(position));
    const std::size_t high = std::min(low + 1, values.size() - 1);
    return values[low] + (position - double(low)) * (values[high] - values[low]);
  };
  double sum = 0.0;
  for (const double value : values) sum += value;
  out.mean = sum / double(values.size());
  out.median = quantile(0.5);
  out.p90 = quantile(0.9);
  out.max = values.back();
  if (values.size() > 1) {
    double squares = 0.0;
    for (const double value : values) squares += (value - out.mean) * (value - out.mean);
    out.sem = std::sqrt(squares / double(values.size() - 1) / double(values.size()));
  }
  return out;
}

nlohmann::json statisticsToJson(const SummaryStatistics& statistics) {
  return {{"mean", statistics.mean}, {"median", statistics.median}, {"p90", statistics.p90},
          {"max", statistics.max},   {"sem", statistics.sem},       {"count", statistics.count}};
}

double sum(const std::vector<double>& values) {
  double total = 0.0;
  for (const double value : values) total += value;
  return total;
}

}  // namespace radquad
