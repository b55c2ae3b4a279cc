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
  out.largestShare = sum == 0.0 ? 0.0 : out.max / sum;
  if (values.size() > 1) {
    double squares = 0.0;
    for (const double value : values) squares += (value - out.mean) * (value - out.mean);
    out.sem = std::sqrt(squares / double(values.size() - 1) / double(values.size()));
  }
  return out;
}

nlohmann::json statisticsToJson(const SummaryStatistics& statistics) {
  return {{"mean", statistics.mean}, {"median", statistics.median}, {"p90", statistics.p90},
          {"max", statistics.max},   {"sem", statistics.sem},       {"count", statistics.count},
          {"largest_share", statistics.largestShare}};
}

double sum(const std::vector<double>& values) {
  double total = 0.0;
  for (const double value : values) total += value;
  return total;
}

}  // namespace radquad
