#include "experiments/study/study_statistics.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "experiments/scenarios/random_stream.h"

namespace radquad {
namespace {

double sumOf(const std::vector<double>& values) {
  double total = 0.0;
  for (const double value : values) total += value;
  return total;
}

// a / b for sums of errors: +inf for a positive numerator over 0, 1 for 0 / 0 (no difference).
double ratioOf(double a, double b) {
  if (b == 0.0) return a == 0.0 ? 1.0 : std::numeric_limits<double>::infinity();
  return a / b;
}

// The type-7 quantile of sorted values (as summarize() in study_metrics.cpp).
double quantile(const std::vector<double>& sorted, double q) {
  const double position = q * double(sorted.size() - 1);
  const std::size_t low = std::size_t(std::floor(position));
  const std::size_t high = std::min(low + 1, sorted.size() - 1);
  if (sorted[low] == sorted[high]) return sorted[low];  // also inf == inf
  return sorted[low] + (position - double(low)) * (sorted[high] - sorted[low]);
}

PairedRatio percentiles(double ratio, std::vector<double>& draws) {
  std::sort(draws.begin(), draws.end());
  return {ratio, quantile(draws, 0.025), quantile(draws, 0.975)};
}

// The sum of one resample (n draws with replacement) of `values`, from `random`.
double resampledSum(const std::vector<double>& values, ScenarioRandom& random) {
  double total = 0.0;
  for (std::size_t k = 0; k < values.size(); ++k) total += values[random.index(values.size())];
  return total;
}

}  // namespace

std::uint64_t bootstrapSeed(std::uint64_t seed, std::uint64_t classIndex) {
  return deriveSeed(seed, {classIndex, 8});
}

PairedRatio pairedRatio(const std::vector<double>& numerator, const std::vector<double>& denominator,
                        std::uint64_t seed, int resamples) {
  const std::size_t n = std::min(numerator.size(), denominator.size());
  PairedRatio out;
  if (n == 0) return out;
  out.ratio = ratioOf(sumOf(numerator), sumOf(denominator));
  out.low = out.high = out.ratio;
  if (n < 2) return out;
  ScenarioRandom random(seed);
  std::vector<double> draws(static_cast<std::size_t>(resamples));
  for (double& draw : draws) {
    double a = 0.0, b = 0.0;
    for (std::size_t k = 0; k < n; ++k) {
      const std::size_t link = std::size_t(random.index(n));
      a += numerator[link];
      b += denominator[link];
    }
    draw = ratioOf(a, b);
  }
  return percentiles(out.ratio, draws);
}

PairedRatio unpairedRatio(const std::vector<double>& numerator,
                          const std::vector<double>& denominator, std::uint64_t seed,
                          int resamples) {
  PairedRatio out;
  if (numerator.empty() || denominator.empty()) return out;
  const double na = double(numerator.size()), nb = double(denominator.size());
  out.ratio = ratioOf(sumOf(numerator) / na, sumOf(denominator) / nb);
  out.low = out.high = out.ratio;
  if (numerator.size() < 2 || denominator.size() < 2) return out;
  ScenarioRandom random(seed);
  std::vector<double> draws(static_cast<std::size_t>(resamples));
  for (double& draw : draws) {
    const double a = resampledSum(numerator, random) / na;
    draw = ratioOf(a, resampledSum(denominator, random) / nb);
  }
  return percentiles(out.ratio, draws);
}

double twoSidedBinomialP(std::size_t n, std::size_t k) {
  k = std::min(k, n - k);
  // log C(n, j) - n log 2, summed from the largest term down so that small terms are not lost.
  const double logHalfPower = -double(n) * std::log(2.0);
  const auto logTerm = [&](std::size_t j) {
    return std::lgamma(double(n) + 1.0) - std::lgamma(double(j) + 1.0) -
           std::lgamma(double(n - j) + 1.0) + logHalfPower;
  };
  const double largest = logTerm(k);
  double total = 0.0;
  for (std::size_t j = k + 1; j-- > 0;) total += std::exp(logTerm(j) - largest);
  return std::min(1.0, 2.0 * std::exp(largest + std::log(total)));
}

SignTest signTest(const std::vector<double>& a, const std::vector<double>& b) {
  SignTest out;
  const std::size_t n = std::min(a.size(), b.size());
  for (std::size_t k = 0; k < n; ++k) {
    if (a[k] < b[k]) {
      ++out.below;
    } else if (a[k] > b[k]) {
      ++out.above;
    } else {
      ++out.ties;
    }
  }
  const std::size_t untied = out.below + out.above;
  out.pValue = untied == 0 ? 1.0 : twoSidedBinomialP(untied, std::min(out.below, out.above));
  return out;
}

LargestShare largestShare(const std::vector<double>& values) {
  LargestShare out;
  const double total = sumOf(values);
  if (values.empty() || total == 0.0) return out;
  out.index = std::size_t(std::max_element(values.begin(), values.end()) - values.begin());
  out.share = values[out.index] / total;
  return out;
}

Influence mostInfluentialPaired(const std::vector<double>& numerator,
                                const std::vector<double>& denominator) {
  Influence out;
  const std::size_t n = std::min(numerator.size(), denominator.size());
  if (n < 2) return out;
  const double a = sumOf(numerator), b = sumOf(denominator), ratio = ratioOf(a, b);
  double strongest = -1.0;
  for (std::size_t k = 0; k < n; ++k) {
    const double ratioWithout = ratioOf(a - numerator[k], b - denominator[k]);
    const double change = std::fabs(std::log(ratioWithout / ratio));
    // NaN (a ratio of 0 without the link and with it) counts as no change.
    if (std::isnan(change) ? false : change > strongest) {
      strongest = change;
      out = {k, false, a == 0.0 ? 0.0 : numerator[k] / a, b == 0.0 ? 0.0 : denominator[k] / b,
             ratioWithout};
    }
  }
  if (strongest < 0.0) out = {0, false, 0.0, 0.0, ratio};
  return out;
}

Influence mostInfluentialUnpaired(const std::vector<double>& numerator,
                                  const std::vector<double>& denominator) {
  Influence out;
  if (numerator.size() < 2 || denominator.size() < 2) return out;
  const double a = sumOf(numerator), b = sumOf(denominator);
  const double na = double(numerator.size()), nb = double(denominator.size());
  const double ratio = ratioOf(a / na, b / nb);
  double strongest = -1.0;
  for (const bool inDenominator : {false, true}) {
    const std::vector<double>& group = inDenominator ? denominator : numerator;
    for (std::size_t k = 0; k < group.size(); ++k) {
      const double ratioWithout = inDenominator ? ratioOf(a / na, (b - group[k]) / (nb - 1.0))
                                                : ratioOf((a - group[k]) / (na - 1.0), b / nb);
      const double change = std::fabs(std::log(ratioWithout / ratio));
      if (std::isnan(change) ? false : change > strongest) {
        strongest = change;
        out = {k, inDenominator, inDenominator || a == 0.0 ? 0.0 : group[k] / a,
               !inDenominator || b == 0.0 ? 0.0 : group[k] / b, ratioWithout};
      }
    }
  }
  if (strongest < 0.0) out = {0, false, 0.0, 0.0, ratio};
  return out;
}

std::vector<double> without(const std::vector<double>& values, std::size_t index) {
  std::vector<double> out;
  out.reserve(values.size());
  for (std::size_t k = 0; k < values.size(); ++k) {
    if (k != index) out.push_back(values[k]);
  }
  return out;
}

}  // namespace radquad
