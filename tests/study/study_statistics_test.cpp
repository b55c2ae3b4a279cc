// The statistics over links (experiments/study/study_statistics.h) against independent
// computations: exact bootstrap distributions enumerated by hand, the binomial closed form of
// the sign test, shares and leave-one-out ratios computed directly.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "experiments/study/study_statistics.h"

namespace radquad {
namespace {

// The exact bootstrap distribution of mean(a) / mean(b) for b = 1: every one of the n^n
// ordered resamples enumerated; its q-quantile (the smallest atom whose CDF reaches q).
double exactBootstrapQuantile(const std::vector<double>& a, double q) {
  const std::size_t n = a.size();
  std::vector<double> means;
  std::vector<std::size_t> pick(n, 0);
  while (true) {
    double total = 0.0;
    for (const std::size_t k : pick) total += a[k];
    means.push_back(total / double(n));
    std::size_t digit = 0;
    while (digit < n && ++pick[digit] == n) pick[digit++] = 0;
    if (digit == n) break;
  }
  std::sort(means.begin(), means.end());
  return means[std::size_t(std::ceil(q * double(means.size()))) - 1];
}

TEST(StudyStatistics, BootstrapIntervalAgainstTheEnumeratedDistribution) {
  // Four links, b = 1: 256 equally likely resamples. The percentiles of 2,000 draws lie
  // between the exact 1.5% and 3.5% (96.5% and 98.5%) quantiles.
  const std::vector<double> a = {1.0, 2.0, 4.0, 8.0}, b(4, 1.0);
  const PairedRatio ratio = pairedRatio(a, b, 11);
  EXPECT_DOUBLE_EQ(ratio.ratio, 15.0 / 4.0);
  EXPECT_GE(ratio.low, exactBootstrapQuantile(a, 0.015));
  EXPECT_LE(ratio.low, exactBootstrapQuantile(a, 0.035));
  EXPECT_GE(ratio.high, exactBootstrapQuantile(a, 0.965));
  EXPECT_LE(ratio.high, exactBootstrapQuantile(a, 0.985));
  // Three links: the smallest drawn three times has probability 1/27 > 2.5%, as has the
  // largest: the interval is [1, 6] exactly.
  const PairedRatio three = pairedRatio({1.0, 2.0, 6.0}, {1.0, 1.0, 1.0}, 11);
  EXPECT_EQ(three.low, 1.0);
  EXPECT_EQ(three.high, 6.0);
}

TEST(StudyStatistics, OneDominatingLinkWidensTheInterval) {
  // 299 links where a = b / 2, one where a = 100 b: ratio (299 0.05 + 100) / (299 0.1 + 1).
  // A resample misses the big link with probability (299/300)^300 = 0.37, and then has ratio
  // 0.5 exactly: the 2.5% percentile is 0.5. The number of copies J of the big link is
  // Binomial(300, 1/300): P(J >= 4) = 0.019 and P(J >= 3) = 0.080, so the 97.5% percentile
  // lies between the ratios of resamples with 3 and with 4 copies.
  std::vector<double> a(300, 0.05), b(300, 0.1);
  a[137] = 100.0;
  b[137] = 1.0;
  const PairedRatio ratio = pairedRatio(a, b, 3);
  EXPECT_NEAR(ratio.ratio, (299 * 0.05 + 100.0) / (299 * 0.1 + 1.0), 1e-12);
  EXPECT_DOUBLE_EQ(ratio.low, 0.5);
  const auto withCopies = [](int j) { return (0.05 * (300 - j) + 100.0 * j) / (0.1 * (300 - j) + j); };
  EXPECT_GE(ratio.high, withCopies(3) * (1 - 1e-12));
  EXPECT_LE(ratio.high, withCopies(4) * (1 + 1e-12));
  // The most influential link and the ratio without it.
  const Influence influence = mostInfluentialPaired(a, b);
  EXPECT_EQ(influence.index, 137u);
  EXPECT_FALSE(influence.inDenominator);
  EXPECT_NEAR(influence.shareOfNumerator, 100.0 / (299 * 0.05 + 100.0), 1e-14);
  EXPECT_NEAR(influence.shareOfDenominator, 1.0 / (299 * 0.1 + 1.0), 1e-14);
  EXPECT_NEAR(influence.ratioWithout, 0.5, 1e-12);  // the sums less the link: cancellation
  const PairedRatio rest = pairedRatio(without(a, 137), without(b, 137), 3);
  EXPECT_NEAR(rest.low, 0.5, 1e-14);
  EXPECT_NEAR(rest.high, 0.5, 1e-14);
}

TEST(StudyStatistics, TheSameSeedGivesTheSameBits) {
  std::vector<double> a, b;
  for (int k = 0; k < 50; ++k) {
    a.push_back(1.0 + std::sin(k));
    b.push_back(1.5 + std::cos(3 * k));
  }
  const PairedRatio first = pairedRatio(a, b, 7), again = pairedRatio(a, b, 7);
  EXPECT_EQ(first.low, again.low);
  EXPECT_EQ(first.high, again.high);
  const PairedRatio other = pairedRatio(a, b, 8);
  EXPECT_NE(first.low, other.low);
  EXPECT_EQ(unpairedRatio(a, b, 7).high, unpairedRatio(a, b, 7).high);
}

TEST(StudyStatistics, PairedIntervalCoversTheTrueRatio) {
  // Pairs b ~ U(1, 2), a = 0.7 b + noise: the 95% interval covers the true ratio of means 0.7
  // in 95% of 400 suites of 100 links, within three binomial standard deviations (0.033).
  std::mt19937_64 random(5);
  std::uniform_real_distribution<double> uniform(1.0, 2.0);
  std::normal_distribution<double> noise(0.0, 0.3);
  int covered = 0;
  for (int suite = 0; suite < 400; ++suite) {
    std::vector<double> a, b;
    for (int link = 0; link < 100; ++link) {
      b.push_back(uniform(random));
      a.push_back(0.7 * b.back() + noise(random));
    }
    const PairedRatio r = pairedRatio(a, b, std::uint64_t(suite));
    covered += r.low <= 0.7 && 0.7 <= r.high ? 1 : 0;
  }
  EXPECT_NEAR(covered / 400.0, 0.95, 0.033);
}

TEST(StudyStatistics, UnpairedIntervalAndInfluence) {
  // Proportional groups of constant values: no spread, the interval is the ratio.
  const PairedRatio flat = unpairedRatio({2, 2, 2}, {4, 4, 4, 4}, 1);
  EXPECT_DOUBLE_EQ(flat.ratio, 0.5);
  EXPECT_DOUBLE_EQ(flat.low, 0.5);
  EXPECT_DOUBLE_EQ(flat.high, 0.5);
  // a = (1, 1, 1, 1, 10), b = 2 everywhere: mean ratio 2.8 / 2; without the 10, 1 / 2; a link
  // of b changes nothing.
  const std::vector<double> a = {1, 1, 1, 1, 10}, b = {2, 2, 2, 2};
  EXPECT_DOUBLE_EQ(unpairedRatio(a, b, 1).ratio, 1.4);
  const Influence influence = mostInfluentialUnpaired(a, b);
  EXPECT_EQ(influence.index, 4u);
  EXPECT_FALSE(influence.inDenominator);
  EXPECT_DOUBLE_EQ(influence.shareOfNumerator, 10.0 / 14.0);
  EXPECT_DOUBLE_EQ(influence.ratioWithout, 0.5);
  // The same with the groups swapped: the link is in the denominator.
  const Influence swapped = mostInfluentialUnpaired(b, a);
  EXPECT_EQ(swapped.index, 4u);
  EXPECT_TRUE(swapped.inDenominator);
  EXPECT_DOUBLE_EQ(swapped.shareOfDenominator, 10.0 / 14.0);
  EXPECT_DOUBLE_EQ(swapped.ratioWithout, 2.0);
  // Resampling the two groups: a resample of a that misses the 10 has mean 1 and ratio 0.5.
  // Its probability (4/5)^5 = 0.33 exceeds 2.5%, so the low percentile is 0.5.
  EXPECT_DOUBLE_EQ(unpairedRatio(a, b, 1).low, 0.5);
}

TEST(StudyStatistics, SignTestAgainstTheBinomialClosedForm) {
  // n = 10 untied, 1 below: 2 (C(10,0) + C(10,1)) / 2^10.
  std::vector<double> a(12, 2.0), b(12, 1.0);
  a[3] = 0.5;
  a[5] = a[7] = 1.0;  // ties
  const SignTest ten = signTest(a, b);
  EXPECT_EQ(ten.below, 1u);
  EXPECT_EQ(ten.above, 9u);
  EXPECT_EQ(ten.ties, 2u);
  EXPECT_NEAR(ten.pValue, 2.0 * 11.0 / 1024.0, 1e-15);
  // n = 20, 5 below: 2 (1 + 20 + 190 + 1140 + 4845 + 15504) / 2^20.
  EXPECT_NEAR(twoSidedBinomialP(20, 5), 2.0 * 21700.0 / 1048576.0, 1e-15);
  EXPECT_NEAR(twoSidedBinomialP(20, 15), 2.0 * 21700.0 / 1048576.0, 1e-15);
  // One rule better on 1 link of 300: 2 (1 + 300) / 2^300, relative to rounding.
  EXPECT_NEAR(twoSidedBinomialP(300, 1) / std::ldexp(602.0, -300), 1.0, 1e-10);
  // Even split: p = 1; nothing untied: p = 1.
  EXPECT_EQ(twoSidedBinomialP(10, 5), 1.0);
  EXPECT_EQ(signTest({1.0, 2.0}, {1.0, 2.0}).pValue, 1.0);
}

TEST(StudyStatistics, LargestShare) {
  const LargestShare share = largestShare({1.0, 2.0, 7.0});
  EXPECT_EQ(share.index, 2u);
  EXPECT_DOUBLE_EQ(share.share, 0.7);
  EXPECT_EQ(largestShare({}).share, 0.0);
  EXPECT_EQ(largestShare({0.0, 0.0}).share, 0.0);
}

}  // namespace
}  // namespace radquad
