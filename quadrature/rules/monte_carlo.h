// Pure Monte Carlo on [0,1]^4: independent uniform points of equal weight.
//
// Citation: N. Metropolis and S. Ulam, "The Monte Carlo method", J. Amer. Statist. Assoc. 44
// (1949); for form factors, Cohen and Wallace, "Radiosity and Realistic Image Synthesis"
// (1993), section 4.9; Gershbein 1995, section 3 ("Pure" sampling).
//
// | name           | samples | parameter                         |
// |----------------|---------|-----------------------------------|
// | `MonteCarlo`   | 81      |                                   |
// | `MonteCarlo:n` | n       | n = 1..10,000,000 points          |
// Degree: none. Seed: point k is drawn from Philox blocks 2k and 2k+1 of stream randomStream(kFamily, 0)
// (quadrature/random/seeds.h).
#pragma once

#include <memory>
#include <string>
#include <string_view>
#include <utility>

#include "quadrature/random/random_rule.h"

namespace radquad {

class MonteCarloRule : public CountedRandomRule {
 public:
  explicit MonteCarloRule(int count, std::string name = "")
      : CountedRandomRule(count, std::move(name), "MonteCarlo") {}

  static constexpr std::string_view kFamily = "Monte Carlo";  // also names its random streams
  std::string family() const override { return std::string(kFamily); }
  std::string citation() const override;
  void drawSamples(std::uint64_t seed, RuleSamples& out) const override;
};

std::shared_ptr<const Rule> makeMonteCarloRule(const std::string& parameter);

}  // namespace radquad
