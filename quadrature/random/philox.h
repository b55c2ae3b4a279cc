// Counter-based random numbers for the random rules: Philox4x32-10.
//
// Citation: J. K. Salmon, M. A. Moraes, R. O. Dror and D. E. Shaw, "Parallel random numbers:
// as easy as 1, 2, 3", SC11 (2011), section 4.2 (Philox-4x32 with R = 10 rounds; multipliers
// 0xD2511F53 and 0xCD9E8D57, key increments 0x9E3779B9 and 0xBB67AE85). Known-answer vectors:
// the Random123 distribution's kat_vectors (checked in tests/quadrature/philox_test.cpp).
//
// A block is a pure function of (counter, key): the random rules key it by their seed and
// count blocks by sample index, so the points of a seed are the same on every machine and
// for every thread count. The conversions to doubles, bounded integers and permutations are
// written out here (no std:: distributions, whose output differs between libraries).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace radquad {

using PhiloxCounter = std::array<std::uint32_t, 4>;
using PhiloxKey = std::array<std::uint32_t, 2>;

// One Philox4x32-10 block.
PhiloxCounter philox4x32(PhiloxCounter counter, PhiloxKey key);

// The key of a 64-bit seed: low word first.
inline PhiloxKey philoxKey(std::uint64_t seed) {
  return {std::uint32_t(seed), std::uint32_t(seed >> 32)};
}

// Blocks for counters (first + k, 0, stream, 0), k = 0..count-1, written word-interleaved:
// out[4k + w] = word w of block k. Computed eight blocks per vector (philox.cpp).
void philoxBlocks(PhiloxKey key, std::uint32_t stream, std::uint32_t first, std::size_t count,
                  std::uint32_t* out);

// Four uniform doubles per point from the two blocks of the point, as the random rules draw
// them: for point p = firstPoint + i, with B = block (2p, 0, stream, 0) and B' = block
// (2p + 1, 0, stream, 0),
//   w01[i] = uniformFromWords(B[0], B[1]),   w23[i] = uniformFromWords(B[2], B[3]),
//   w45[i] = uniformFromWords(B'[0], B'[1]), w67[i] = uniformFromWords(B'[2], B'[3]),
// the same values as philoxBlocks(key, stream, 2 firstPoint, 2 count, ...) converted word
// pair by word pair, without storing the words. Requires 2 (firstPoint + count) <= 2^32.
void philoxUniformQuads(PhiloxKey key, std::uint32_t stream, std::uint32_t firstPoint,
                        std::size_t count, double* w01, double* w23, double* w45, double* w67);

// The same for a list of points: point points[i] (each below 2^31) gives w01[i] .. w67[i].
void philoxUniformQuadsAt(PhiloxKey key, std::uint32_t stream, const std::uint32_t* points,
                          std::size_t count, double* w01, double* w23, double* w45, double* w67);

// A double in [0,1) from 53 random bits: (hi:lo >> 11) 2^-53.
inline double uniformFromWords(std::uint32_t hi, std::uint32_t lo) {
  const std::uint64_t bits = (std::uint64_t(hi) << 32) | lo;
  return double(bits >> 11) * 0x1.0p-53;
}

// A sequential stream of words from blocks (0..), (1..), ... of one (key, stream); for the
// draws that must come one after another (the N-rooks permutations).
class PhiloxStream {
 public:
  PhiloxStream(std::uint64_t seed, std::uint32_t stream) : key_(philoxKey(seed)), stream_(stream) {}

  std::uint32_t nextWord();
  double uniform() {
    const std::uint32_t hi = nextWord();
    return uniformFromWords(hi, nextWord());
  }
  // Uniform in [0, bound), bound >= 1, without modulo bias: Lemire's multiply-and-reject
  // (D. Lemire, "Fast random integer generation in an interval", ACM TOMACS 29(1), 2019).
  std::uint32_t bounded(std::uint32_t bound);
  // A uniformly random permutation of 0..n-1 (Fisher-Yates, Knuth TAOCP vol. 2, 3.4.2 P).
  void permutation(std::size_t n, std::vector<std::uint32_t>& out);

 private:
  PhiloxKey key_;
  std::uint32_t stream_;
  std::uint32_t block_ = 0;
  PhiloxCounter words_{};
  int used_ = 4;
};


}  // namespace radquad
