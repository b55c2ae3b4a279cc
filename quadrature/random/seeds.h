// Seeds and stream numbers: every seed radquad derives from a user's seed, and every Philox
// stream number a random rule draws from, comes from this header, through one 64-bit mix.
//
// The mix is SplitMix64's finaliser (G. L. Steele, D. Lea and C. H. Flood, "Fast splittable
// pseudorandom number generators", OOPSLA 2014), a bijection of 64-bit words that spreads
// every input bit over the output: derived seeds of nearby index tuples are unrelated.
#pragma once

#include <cstdint>
#include <initializer_list>
#include <string_view>

namespace radquad {

// The SplitMix64 finaliser.
inline constexpr std::uint64_t mix64(std::uint64_t z) {
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

// A seed derived from a parent seed and a list of indices (class, link, purpose, trial ...;
// a link's receiver and source): each index is folded in with a mix.
inline constexpr std::uint64_t deriveSeed(std::uint64_t seed,
                                          std::initializer_list<std::uint64_t> indices) {
  std::uint64_t state = mix64(seed + 0x9e3779b97f4a7c15ULL);
  for (const std::uint64_t index : indices) state = mix64(state ^ mix64(index + 0x632be59bd9b4e019ULL));
  return state;
}

// Replicate `index` of a seed: replicate 0 is the seed itself (so a reported draw and the
// first of its replicates agree), the others deriveSeed(seed, {index}).
inline constexpr std::uint64_t replicateSeed(std::uint64_t seed, std::uint32_t index) {
  return index == 0 ? seed : deriveSeed(seed, {index});
}

// The Philox stream number a random rule family draws from for one purpose (0, 1, ...: the
// N-rooks rule uses one for its jitter and one for its permutations): a 32-bit hash of the
// family's name (FNV-1a, 64 bits) and the purpose, mixed. A new family gets its own streams
// from its name, with nothing to register; tests/quadrature/random_rules_test.cpp checks that
// the registered families' streams are distinct.
inline constexpr std::uint32_t randomStream(std::string_view family, std::uint32_t purpose) {
  std::uint64_t hash = 0xcbf29ce484222325ULL;
  for (const char c : family) hash = (hash ^ std::uint8_t(c)) * 0x100000001b3ULL;
  return std::uint32_t(mix64(hash ^ mix64(purpose)) >> 32);
}

}  // namespace radquad
