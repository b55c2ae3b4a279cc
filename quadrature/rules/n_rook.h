// N-rooks sampling (Latin hypercube) on [0,1]^4: each axis is cut into n strata and every
// stratum of every axis holds exactly one of the n points, jittered uniformly inside it; the
// strata are matched across axes by independent random permutations.
//
// Citation: M. D. McKay, R. J. Beckman and W. J. Conover, "A comparison of three methods for
// selecting values of input variables in the analysis of output from a computer code",
// Technometrics 21 (1979); P. Shirley, "Discrepancy as a quality measure for sampling
// distributions", Eurographics '91 (N-rooks); Gershbein 1995, section 3.
//
// | name      | samples | parameter                 |
// |-----------|---------|---------------------------|
// | `NRook`   | 81      |                           |
// | `NRook:n` | n       | n = 1..10,000,000 points  |
// Degree: none. Seed: the four permutations come, in axis order s, t, u, v, from one
// sequential Philox stream (randomStream(kFamily, 1)); the jitter of point k from blocks 2k, 2k+1
// of stream randomStream(kFamily, 0). Point k has coordinate (perm_axis[k] + jitter) / n on each axis.
#pragma once

#include <memory>
#include <string>
#include <string_view>
#include <utility>

#include "quadrature/random/random_rule.h"

namespace radquad {

class NRookRule : public CountedRandomRule {
 public:
  explicit NRookRule(int count, std::string name = "")
      : CountedRandomRule(count, std::move(name), "NRook") {}

  static constexpr std::string_view kFamily = "N-rooks Monte Carlo";  // also names its random streams
  std::string family() const override { return std::string(kFamily); }
  std::string citation() const override;
  void drawSamples(std::uint64_t seed, RuleSamples& out) const override;
};

std::shared_ptr<const Rule> makeNRookRule(const std::string& parameter);

}  // namespace radquad
