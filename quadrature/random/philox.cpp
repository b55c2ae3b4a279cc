#include "quadrature/random/philox.h"

#include <algorithm>
#include <cstring>
#if defined(__AVX512F__)
#include <immintrin.h>
#endif

#include "kernel/simd_lanes.h"

namespace radquad {
namespace {

constexpr std::uint32_t kMultiplier0 = 0xD2511F53u;
constexpr std::uint32_t kMultiplier1 = 0xCD9E8D57u;
constexpr std::uint32_t kWeyl0 = 0x9E3779B9u;
constexpr std::uint32_t kWeyl1 = 0xBB67AE85u;

// One Philox-4x32 round (Salmon et al. 2011, section 4.2): words 0 and 2 are multiplied by
// the two multipliers; the high halves, xored with words 1 and 3 and the round key, and the
// low halves make the next block (with the words permuted as in Random123).
inline void philoxRound(std::uint32_t& c0, std::uint32_t& c1, std::uint32_t& c2, std::uint32_t& c3,
                        std::uint32_t k0, std::uint32_t k1) {
  const std::uint64_t product0 = std::uint64_t(kMultiplier0) * c0;
  const std::uint64_t product1 = std::uint64_t(kMultiplier1) * c2;
  const std::uint32_t n0 = std::uint32_t(product1 >> 32) ^ c1 ^ k0;
  const std::uint32_t n1 = std::uint32_t(product1);
  const std::uint32_t n2 = std::uint32_t(product0 >> 32) ^ c3 ^ k1;
  const std::uint32_t n3 = std::uint32_t(product0);
  c0 = n0;
  c1 = n1;
  c2 = n2;
  c3 = n3;
}

inline void philox10(std::uint32_t& c0, std::uint32_t& c1, std::uint32_t& c2, std::uint32_t& c3,
                     std::uint32_t k0, std::uint32_t k1) {
  for (int round = 0; round < 10; ++round) {
    philoxRound(c0, c1, c2, c3, k0, k1);
    k0 += kWeyl0;
    k1 += kWeyl1;
  }
}

}  // namespace

PhiloxCounter philox4x32(PhiloxCounter counter, PhiloxKey key) {
  philox10(counter[0], counter[1], counter[2], counter[3], key[0], key[1]);
  return counter;
}

namespace {

// Philox blocks side by side, one block per 64-bit lane of an 8-lane vector (GCC/Clang vector
// extension). Only the low 32 bits of a lane are a word of the block: the round reads the
// multiplicands' low halves only, so the high halves may carry junk and are never masked
// inside the rounds.
using BlockLanes = simd::UInt64s8;
using DoubleLanes = simd::Doubles8;
constexpr int kBlockLanes = simd::kLanes;

// lo32(a) * m (m < 2^32) in every lane: Philox's 32 x 32 -> 64-bit product. AVX-512 has it as
// one instruction (vpmuludq), which compilers do not find from the portable form; the
// portable form is the fallback and gives the same bits.
inline BlockLanes wideProduct(BlockLanes a, BlockLanes m) {
#if defined(__AVX512F__)
  return BlockLanes(_mm512_mul_epu32(__m512i(a), __m512i(m)));
#else
  return (a & 0xffffffffu) * m;
#endif
}

// The ten rounds on G independent vectors of blocks (independent chains hide the multiply
// latency); word w of the blocks of vector g is in c[w][g]. Same round as philoxRound.
template <int G>
inline void philoxRoundsOnLanes(BlockLanes (&c)[4][G], PhiloxKey key) {
  const BlockLanes multiplier0 = BlockLanes{} + kMultiplier0;
  const BlockLanes multiplier1 = BlockLanes{} + kMultiplier1;
  std::uint32_t k0 = key[0], k1 = key[1];
  for (int round = 0; round < 10; ++round) {
    const BlockLanes key0 = BlockLanes{} + k0, key1 = BlockLanes{} + k1;
#pragma GCC unroll 8
    for (int g = 0; g < G; ++g) {
      const BlockLanes product0 = wideProduct(c[0][g], multiplier0);
      const BlockLanes product1 = wideProduct(c[2][g], multiplier1);
      c[0][g] = (product1 >> 32) ^ c[1][g] ^ key0;
      c[1][g] = product1;
      c[2][g] = (product0 >> 32) ^ c[3][g] ^ key1;
      c[3][g] = product0;
    }
    k0 += kWeyl0;
    k1 += kWeyl1;
  }
}

// Counters (first + lane, 0, stream, 0) of one vector of blocks.
template <int G>
inline void setCounters(BlockLanes (&c)[4][G], int g, BlockLanes first, std::uint32_t stream) {
  c[0][g] = first + BlockLanes{0, 1, 2, 3, 4, 5, 6, 7};
  c[1][g] = BlockLanes{};
  c[2][g] = BlockLanes{} + stream;
  c[3][g] = BlockLanes{};
}

// uniformFromWords(hi, lo) in every lane.
inline DoubleLanes uniformLanes(BlockLanes hi, BlockLanes lo) {
  const BlockLanes bits = ((hi << 32) | (lo & 0xffffffffu)) >> 11;
  return __builtin_convertvector(bits, DoubleLanes) * 0x1.0p-53;
}

// The first `count` lanes to `to`: one vector store when all 8 are wanted.
inline void storeLanes(double* to, DoubleLanes lanes, std::size_t count) {
  if (count == kBlockLanes) {
    std::memcpy(to, &lanes, sizeof(lanes));
    return;
  }
  for (std::size_t lane = 0; lane < count; ++lane) to[lane] = lanes[lane];
}

}  // namespace

void philoxBlocks(PhiloxKey key, std::uint32_t stream, std::uint32_t first, std::size_t count,
                  std::uint32_t* __restrict out) {
  constexpr int G = 2;
  constexpr std::size_t kStep = G * kBlockLanes;
  std::size_t k = 0;
  for (; k + kStep <= count; k += kStep) {
    BlockLanes c[4][G];
    for (int g = 0; g < G; ++g) {
      setCounters(c, g, BlockLanes{} + std::uint32_t(first + k + g * kBlockLanes), stream);
    }
    philoxRoundsOnLanes(c, key);
    for (int g = 0; g < G; ++g) {
      for (int lane = 0; lane < kBlockLanes; ++lane) {
        for (int w = 0; w < 4; ++w) {
          out[4 * (k + std::size_t(g * kBlockLanes + lane)) + std::size_t(w)] =
              std::uint32_t(c[w][g][lane]);
        }
      }
    }
  }
  for (; k < count; ++k) {
    const PhiloxCounter block = philox4x32({first + std::uint32_t(k), 0, stream, 0}, key);
    for (int w = 0; w < 4; ++w) out[4 * k + w] = block[w];
  }
}

namespace {

// philoxUniformQuads for the points `pointAt(i)`, i = 0..count-1 (a contiguous range or a
// list): sixteen points per step, their even and odd blocks in four vectors.
template <class PointLanes>
void uniformQuads(PhiloxKey key, std::uint32_t stream, std::size_t count,
                  const PointLanes& pointLanes, double* __restrict w01, double* __restrict w23,
                  double* __restrict w45, double* __restrict w67) {
  constexpr int G = 4;
  constexpr std::size_t kStep = 2 * kBlockLanes;
  for (std::size_t p = 0; p < count; p += kStep) {
    BlockLanes c[4][G];
    for (int half = 0; half < 2; ++half) {
      const BlockLanes point = pointLanes(p + std::size_t(half) * kBlockLanes);
      for (int odd = 0; odd < 2; ++odd) {
        setCounters(c, 2 * half + odd, BlockLanes{}, stream);
        c[0][2 * half + odd] = std::uint32_t(2) * point + std::uint32_t(odd);
      }
    }
    philoxRoundsOnLanes(c, key);
    for (int half = 0; half < 2; ++half) {
      const std::size_t start = p + std::size_t(half) * kBlockLanes;
      if (start >= count) break;
      const std::size_t lanes = std::min<std::size_t>(kBlockLanes, count - start);
      const int even = 2 * half, odd = 2 * half + 1;
      storeLanes(w01 + start, uniformLanes(c[0][even], c[1][even]), lanes);
      storeLanes(w23 + start, uniformLanes(c[2][even], c[3][even]), lanes);
      storeLanes(w45 + start, uniformLanes(c[0][odd], c[1][odd]), lanes);
      storeLanes(w67 + start, uniformLanes(c[2][odd], c[3][odd]), lanes);
    }
  }
}

}  // namespace

void philoxUniformQuads(PhiloxKey key, std::uint32_t stream, std::uint32_t firstPoint,
                        std::size_t count, double* __restrict w01, double* __restrict w23,
                        double* __restrict w45, double* __restrict w67) {
  uniformQuads(
      key, stream, count,
      [firstPoint](std::size_t i) {
        return BlockLanes{0, 1, 2, 3, 4, 5, 6, 7} + std::uint32_t(firstPoint + i);
      },
      w01, w23, w45, w67);
}

void philoxUniformQuadsAt(PhiloxKey key, std::uint32_t stream, const std::uint32_t* points,
                          std::size_t count, double* __restrict w01, double* __restrict w23,
                          double* __restrict w45, double* __restrict w67) {
  uniformQuads(
      key, stream, count,
      [points, count](std::size_t i) {
        // Lanes past the list repeat its last point (computed, never stored).
        BlockLanes lanes;
        for (int lane = 0; lane < kBlockLanes; ++lane) {
          lanes[lane] = points[std::min(i + std::size_t(lane), count - 1)];
        }
        return lanes;
      },
      w01, w23, w45, w67);
}

std::uint32_t PhiloxStream::nextWord() {
  if (used_ == 4) {
    words_ = philox4x32({block_++, 0, stream_, 0}, key_);
    used_ = 0;
  }
  return words_[used_++];
}

std::uint32_t PhiloxStream::bounded(std::uint32_t bound) {
  std::uint64_t product = std::uint64_t(nextWord()) * bound;
  std::uint32_t low = std::uint32_t(product);
  if (low < bound) {
    const std::uint32_t threshold = std::uint32_t(-bound) % bound;  // 2^32 mod bound
    while (low < threshold) {
      product = std::uint64_t(nextWord()) * bound;
      low = std::uint32_t(product);
    }
  }
  return std::uint32_t(product >> 32);
}

void PhiloxStream::permutation(std::size_t n, std::vector<std::uint32_t>& out) {
  out.resize(n);
  for (std::size_t i = 0; i < n; ++i) out[i] = std::uint32_t(i);
  for (std::size_t i = n; i > 1; --i) {
    const std::uint32_t j = bounded(std::uint32_t(i));
    std::swap(out[i - 1], out[j]);
  }
}

}  // namespace radquad
