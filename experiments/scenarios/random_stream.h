// An explicit, portable random stream for scenario generation: SplitMix64 (Steele, Lea and
// Flood, "Fast splittable pseudorandom number generators", OOPSLA 2014). The output is a
// pure function of the seed, so suites are identical on every machine, library and thread
// count (std:: distributions are not: their algorithms are implementation-defined).
#pragma once

#include <cmath>
#include <cstdint>
#include <initializer_list>

namespace radquad {

// The SplitMix64 finaliser: a bijective 64-bit mix.
inline constexpr std::uint64_t mix64(std::uint64_t z) {
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

// A seed derived from a parent seed and a list of indices (class, link, purpose, trial...):
// each index is folded in with a mix, so nearby index tuples give unrelated seeds.
inline std::uint64_t deriveSeed(std::uint64_t seed, std::initializer_list<std::uint64_t> indices) {
  std::uint64_t state = mix64(seed + 0x9e3779b97f4a7c15ULL);
  for (const std::uint64_t index : indices)
    state = mix64(state ^ mix64(index + 0x632be59bd9b4e019ULL));
  return state;
}

class ScenarioRandom {
 public:
  explicit ScenarioRandom(std::uint64_t seed) : state_(seed) {}

  std::uint64_t next() {
    state_ += 0x9e3779b97f4a7c15ULL;
    return mix64(state_);
  }
  // Uniform in [0, 1) with 53 random bits.
  double uniform() { return double(next() >> 11) * 0x1.0p-53; }
  double uniform(double low, double high) { return low + (high - low) * uniform(); }
  // Log-uniform in [low, high] (both positive): scale-free ranges of sizes and distances.
  double logUniform(double low, double high) {
    return low * std::exp(uniform() * std::log(high / low));
  }
  // Uniform integer in [0, count); the slight modulo bias is irrelevant for small counts.
  std::uint64_t index(std::uint64_t count) { return next() % count; }

 private:
  std::uint64_t state_;
};

}  // namespace radquad
