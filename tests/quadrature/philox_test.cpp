// Philox4x32-10 against the Random123 known-answer vectors, and the conversions built on it.
#include "quadrature/random/philox.h"
#include "quadrature/random/seeds.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace radquad {
namespace {

// Random123 kat_vectors, "philox4x32 10" lines (counter, key, expected output).
TEST(Philox, MatchesRandom123KnownAnswers) {
  EXPECT_EQ(philox4x32({0, 0, 0, 0}, {0, 0}),
            (PhiloxCounter{0x6627e8d5u, 0xe169c58du, 0xbc57ac4cu, 0x9b00dbd8u}));
  EXPECT_EQ(
      philox4x32({0xffffffffu, 0xffffffffu, 0xffffffffu, 0xffffffffu}, {0xffffffffu, 0xffffffffu}),
      (PhiloxCounter{0x408f276du, 0x41c83b0eu, 0xa20bc7c6u, 0x6d5451fdu}));
  EXPECT_EQ(
      philox4x32({0x243f6a88u, 0x85a308d3u, 0x13198a2eu, 0x03707344u}, {0xa4093822u, 0x299f31d0u}),
      (PhiloxCounter{0xd16cfe09u, 0x94fdccebu, 0x5001e420u, 0x24126ea1u}));
}

TEST(Philox, BatchedBlocksEqualSingleBlocks) {
  const PhiloxKey key = philoxKey(0x0123456789abcdefull);
  const std::size_t count = 37;  // two full lanes of 16 and a tail
  std::vector<std::uint32_t> words(4 * count);
  philoxBlocks(key, 5, 1000, count, words.data());
  for (std::size_t k = 0; k < count; ++k) {
    const PhiloxCounter block = philox4x32({1000u + std::uint32_t(k), 0, 5, 0}, key);
    for (int w = 0; w < 4; ++w) ASSERT_EQ(words[4 * k + w], block[w]) << "block " << k;
  }
}

// The vectorised paths on the first Random123 vector (counter 0, key 0): block 0 of stream 0.
TEST(Philox, VectorisedPathsMatchRandom123KnownAnswer) {
  std::vector<std::uint32_t> words(4 * 16);
  philoxBlocks({0, 0}, 0, 0, 16, words.data());  // one full pass of the 8-lane vectors
  EXPECT_EQ(words[0], 0x6627e8d5u);
  EXPECT_EQ(words[1], 0xe169c58du);
  EXPECT_EQ(words[2], 0xbc57ac4cu);
  EXPECT_EQ(words[3], 0x9b00dbd8u);
  double w01 = 0, w23 = 0, w45 = 0, w67 = 0;
  philoxUniformQuads({0, 0}, 0, 0, 1, &w01, &w23, &w45, &w67);
  EXPECT_EQ(w01, uniformFromWords(0x6627e8d5u, 0xe169c58du));
  EXPECT_EQ(w23, uniformFromWords(0xbc57ac4cu, 0x9b00dbd8u));
}

// philoxUniformQuads against single scalar blocks: point p uses blocks 2p and 2p+1. Counts
// that are not multiples of the 16 points per pass, and points near the top of the counter.
TEST(Philox, UniformQuadsEqualSingleBlocks) {
  const PhiloxKey key = philoxKey(0xfedcba9876543210ull);
  for (const auto& [first, count] : {std::pair<std::uint32_t, std::size_t>{0, 1},
                                     {1000, 37},
                                     {5, 256},
                                     {0x7fffffffu - 40, 41}}) {
    std::vector<double> w01(count), w23(count), w45(count), w67(count);
    philoxUniformQuads(key, 9, first, count, w01.data(), w23.data(), w45.data(), w67.data());
    for (std::size_t i = 0; i < count; ++i) {
      const std::uint32_t p = first + std::uint32_t(i);
      const PhiloxCounter even = philox4x32({2 * p, 0, 9, 0}, key);
      const PhiloxCounter odd = philox4x32({2 * p + 1, 0, 9, 0}, key);
      ASSERT_EQ(w01[i], uniformFromWords(even[0], even[1])) << "point " << p;
      ASSERT_EQ(w23[i], uniformFromWords(even[2], even[3])) << "point " << p;
      ASSERT_EQ(w45[i], uniformFromWords(odd[0], odd[1])) << "point " << p;
      ASSERT_EQ(w67[i], uniformFromWords(odd[2], odd[3])) << "point " << p;
    }
  }
}

TEST(Philox, UniformDoublesCoverTheUnitIntervalEvenly) {
  EXPECT_EQ(uniformFromWords(0, 0), 0.0);
  EXPECT_LT(uniformFromWords(0xffffffffu, 0xffffffffu), 1.0);
  EXPECT_EQ(uniformFromWords(0x80000000u, 0), 0.5);
  // Chi-square over 16 bins of 160,000 draws: 15 degrees of freedom, 99.9% quantile 37.7.
  PhiloxStream stream(7, 0);
  const int bins = 16, draws = 160000;
  std::vector<int> counts(bins, 0);
  for (int i = 0; i < draws; ++i) ++counts[int(stream.uniform() * bins)];
  double chiSquare = 0.0;
  const double expected = double(draws) / bins;
  for (int c : counts) chiSquare += (c - expected) * (c - expected) / expected;
  EXPECT_LT(chiSquare, 37.7);
}

TEST(Philox, BoundedIntegersAreInRangeAndUnbiased) {
  PhiloxStream stream(11, 0);
  // 3 does not divide 2^32: a modulo reduction would be biased (slightly); check the range
  // and a chi-square over the 3 values (2 dof, 99.9% quantile 13.8).
  std::vector<int> counts(3, 0);
  for (int i = 0; i < 300000; ++i) {
    const std::uint32_t value = stream.bounded(3);
    ASSERT_LT(value, 3u);
    ++counts[value];
  }
  double chiSquare = 0.0;
  for (int c : counts) chiSquare += (c - 100000.0) * (c - 100000.0) / 100000.0;
  EXPECT_LT(chiSquare, 13.8);
  for (int i = 0; i < 1000; ++i) EXPECT_EQ(stream.bounded(1), 0u);
}

TEST(Philox, PermutationsArePermutationsAndUniform) {
  PhiloxStream stream(3, 0);
  std::vector<std::uint32_t> permutation;
  // Over 60,000 shuffles of 3 items, each of the 6 orders appears about 10,000 times
  // (5 dof, 99.9% quantile 20.5).
  std::vector<int> counts(6, 0);
  for (int i = 0; i < 60000; ++i) {
    stream.permutation(3, permutation);
    std::vector<std::uint32_t> sorted = permutation;
    std::sort(sorted.begin(), sorted.end());
    ASSERT_EQ(sorted, (std::vector<std::uint32_t>{0, 1, 2}));
    const int code = int(permutation[0]) * 2 + (permutation[1] > permutation[2] ? 1 : 0);
    ++counts[code];
  }
  double chiSquare = 0.0;
  for (int c : counts) chiSquare += (c - 10000.0) * (c - 10000.0) / 10000.0;
  EXPECT_LT(chiSquare, 20.5);
}

TEST(Seeds, ReplicateZeroIsTheSeedAndTheOthersDiffer) {
  EXPECT_EQ(replicateSeed(42, 0), 42u);
  EXPECT_NE(replicateSeed(42, 1), replicateSeed(42, 2));
  EXPECT_NE(replicateSeed(42, 1), replicateSeed(43, 1));
  EXPECT_NE(replicateSeed(42, 1), 43u);
  EXPECT_NE(deriveSeed(7, {1, 2}), deriveSeed(7, {2, 1}));
}

// The mix is SplitMix64's: the published generator (state += 0x9e3779b97f4a7c15, output the
// finaliser of the state) gives 0xe220a8397b1dcdaf first from state 0 (Vigna's splitmix64.c).
TEST(Seeds, MixIsSplitMix64) {
  EXPECT_EQ(mix64(0x9e3779b97f4a7c15ULL), 0xe220a8397b1dcdafULL);
}

}  // namespace
}  // namespace radquad
