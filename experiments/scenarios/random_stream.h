// An explicit, portable random stream for scenario generation: SplitMix64 (Steele, Lea and
// Flood, "Fast splittable pseudorandom number generators", OOPSLA 2014). The output is a
// pure function of the seed, so suites are identical on every machine, library and thread
// count (std:: distributions are not: their algorithms are implementation-defined). Seeds
// are derived with deriveSeed (quadrature/random/seeds.h).
#pragma once

#include <cmath>
#include <cstdint>

#include "quadrature/random/seeds.h"

namespace radquad {

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
