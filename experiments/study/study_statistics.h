// Statistics over a suite's links that one link cannot decide (docs/study.md, "Statistics"):
// the ratio of two rules' mean errors with a bootstrap interval over links, a sign test on the
// per-link differences, the share of the largest link in a mean, and the link whose removal
// moves a ratio the most (leave-one-out).
//
// Why a bootstrap: a suite's errors are heavy-tailed, and a few links (a touching pair, a
// shadow edge crossing a close link) can carry most of both means of a ratio. The delta
// method linearises the ratio around the full-suite value and gives such a ratio a narrow
// interval; resampling the links (Efron and Tibshirani 1993, "An Introduction to the
// Bootstrap", ch. 13: the percentile interval) lets the interval see the suites with that
// link absent or repeated. The resamples are drawn from a seed (SplitMix64,
// experiments/scenarios/random_stream.h), so every interval is the same bits on every run,
// and comparisons drawn with one seed on the same links share their resamples.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace radquad {

// Resamples of every bootstrap interval: enough for 2.5% and 97.5% percentiles (Efron and
// Tibshirani recommend at least 1,000 for percentile intervals).
inline constexpr int kBootstrapResamples = 2000;

// The seed of every bootstrap over the links of class `classIndex` (unoccluded 0, partial 1,
// ...) of a suite whose config seed is `seed`: deriveSeed(seed, {classIndex, 8}), beside the
// per-candidate seeds of docs/study.md, "Seeds". The report's claims use the same seeds, so a
// claim's interval and the table's are drawn from the same resamples.
std::uint64_t bootstrapSeed(std::uint64_t seed, std::uint64_t classIndex);

// A ratio of means with its 95% interval.
struct PairedRatio {
  double ratio = 0.0, low = 0.0, high = 0.0;
};

// Paired samples (the same links): sum a_i / sum b_i, and the 2.5% and 97.5% percentiles of
// that ratio over `resamples` resamples of the links with replacement (the quantile of
// summarize(), study_metrics.h). A resample whose denominator is 0 counts as +inf (as 1 when
// its numerator is 0 too). Fewer than 2 links: the interval is the ratio itself.
PairedRatio pairedRatio(const std::vector<double>& numerator, const std::vector<double>& denominator,
                        std::uint64_t seed, int resamples = kBootstrapResamples);

// Independent samples (different links): mean(a) / mean(b), each group resampled on its own.
PairedRatio unpairedRatio(const std::vector<double>& numerator,
                          const std::vector<double>& denominator, std::uint64_t seed,
                          int resamples = kBootstrapResamples);

// The sign test of paired samples: the links where a_i < b_i (below), a_i > b_i (above) and
// ties; the two-sided p-value of the exact binomial test with p = 1/2 on the untied links,
// min(1, 2 P(X <= min(below, above))), X ~ Binomial(below + above, 1/2). It answers another
// question than the ratio of means: on how many links one rule wins, whatever the sizes.
struct SignTest {
  std::size_t below = 0, above = 0, ties = 0;
  double pValue = 1.0;
};
SignTest signTest(const std::vector<double>& a, const std::vector<double>& b);

// min(1, 2 P(X <= k)) for X ~ Binomial(n, 1/2), k <= n (summed in logarithms, exact to
// rounding for any n).
double twoSidedBinomialP(std::size_t n, std::size_t k);

// The largest value's share of the sum (of a mean over links), and its index; 0 when the sum
// is 0.
struct LargestShare {
  std::size_t index = 0;
  double share = 0.0;
};
LargestShare largestShare(const std::vector<double>& values);

// The most influential link of a ratio of means: the one whose removal changes the ratio by
// the largest factor (|log(ratio without it / ratio)|), its shares of the numerator's and the
// denominator's sums, and the ratio without it. Unpaired: a link of either group
// (`inDenominator` says which; shares are of its own group's sum).
struct Influence {
  std::size_t index = 0;
  bool inDenominator = false;
  double shareOfNumerator = 0.0, shareOfDenominator = 0.0;
  double ratioWithout = 0.0;
};
Influence mostInfluentialPaired(const std::vector<double>& numerator,
                                const std::vector<double>& denominator);
Influence mostInfluentialUnpaired(const std::vector<double>& numerator,
                                  const std::vector<double>& denominator);

// The values without the one at `index`.
std::vector<double> without(const std::vector<double>& values, std::size_t index);

}  // namespace radquad
