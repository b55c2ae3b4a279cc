// What the random rules (MonteCarlo, NRook, Stratified) share: no declared degree, a seed,
// equal weights 1/N, and the parsing of their parameter. Their points come from Philox
// blocks keyed by the seed (quadrature/random/philox.h), in streams named by their family
// (randomStream in quadrature/random/seeds.h), so a seed gives the same points on
// every machine and thread count.
#pragma once

#include <cstdint>
#include <string>
#include <utility>

#include "quadrature/rule.h"

namespace radquad {

class RandomPointRule : public Rule {
 public:
  std::optional<int> degree() const override { return std::nullopt; }
  bool isRandom() const override { return true; }
  RuleSamples samples(std::uint64_t seed) const override {
    RuleSamples drawn;
    drawSamples(seed, drawn);
    return drawn;
  }
  void drawSamples(std::uint64_t seed, RuleSamples& out) const override = 0;
};

// A random rule of `count` points (MonteCarlo, NRook), named "PREFIX:count" unless given
// another name.
class CountedRandomRule : public RandomPointRule {
 public:
  std::string name() const override { return name_; }
  std::size_t sampleCount() const override { return std::size_t(count_); }

 protected:
  CountedRandomRule(int count, std::string name, const std::string& prefix)
      : count_(count),
        name_(name.empty() ? prefix + ":" + std::to_string(count) : std::move(name)) {}

 private:
  int count_;
  std::string name_;
};

// Resizes `out` to a 4D point set of `count` points of weight 1/count.
void resizeEqualWeights(std::size_t count, RuleSamples& out);

// Parses the integer after the colon of a parametrised name (e.g. "81" of "NRook:81");
// InputError names the rule and the allowed range.
int parseRuleParameter(const std::string& family, const std::string& parameter, int minimum,
                       int maximum, const char* meaning);

}  // namespace radquad
