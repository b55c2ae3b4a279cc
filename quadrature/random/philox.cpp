#include "quadrature/random/philox.h"

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

void philoxBlocks(PhiloxKey key, std::uint32_t stream, std::uint32_t first, std::size_t count,
                  std::uint32_t* __restrict out) {
  // Lanes of 16 blocks in registers; the compiler turns the rounds into vector multiplies.
  constexpr std::size_t kLanes = 16;
  std::size_t k = 0;
  for (; k + kLanes <= count; k += kLanes) {
    std::uint32_t c0[kLanes], c1[kLanes], c2[kLanes], c3[kLanes];
    for (std::size_t lane = 0; lane < kLanes; ++lane) {
      c0[lane] = first + std::uint32_t(k + lane);
      c1[lane] = 0;
      c2[lane] = stream;
      c3[lane] = 0;
    }
    std::uint32_t k0 = key[0], k1 = key[1];
    for (int round = 0; round < 10; ++round) {
      for (std::size_t lane = 0; lane < kLanes; ++lane) {
        philoxRound(c0[lane], c1[lane], c2[lane], c3[lane], k0, k1);
      }
      k0 += kWeyl0;
      k1 += kWeyl1;
    }
    for (std::size_t lane = 0; lane < kLanes; ++lane) {
      out[4 * (k + lane) + 0] = c0[lane];
      out[4 * (k + lane) + 1] = c1[lane];
      out[4 * (k + lane) + 2] = c2[lane];
      out[4 * (k + lane) + 3] = c3[lane];
    }
  }
  for (; k < count; ++k) {
    const PhiloxCounter block = philox4x32({first + std::uint32_t(k), 0, stream, 0}, key);
    for (int w = 0; w < 4; ++w) out[4 * k + w] = block[w];
  }
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

std::uint64_t derivedSeed(std::uint64_t seed, std::uint32_t index) {
  if (index == 0) return seed;
  // A block under a fixed key separates the derived seeds from the user's seeds S, S+1, ...
  const PhiloxCounter block =
      philox4x32({std::uint32_t(seed), std::uint32_t(seed >> 32), index, 0x7265706cu},
                 {0x52616451u, 0x75616452u});
  return (std::uint64_t(block[0]) << 32) | block[1];
}

}  // namespace radquad
