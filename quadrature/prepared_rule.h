// A rule bound to a basis degree, ready to integrate many links. Deterministic rules keep
// their points and weighted basis tables, built once, and so do rules given as a list of
// draws (one per trial); random rules draw their points from the seed of each call.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "kernel/coupling.h"
#include "quadrature/rule.h"

namespace radquad {

class PreparedRule {
 public:
  PreparedRule(std::shared_ptr<const Rule> rule, int degree);

  const Rule& rule() const { return *rule_; }
  int degree() const { return degree_; }

  // Integrates the coupling of one link: a random rule's draw for `seed`, or for a rule of
  // listed draws draw `trial` (InputError past the last; the caller checks the trials it
  // asks with checkDrawCount). Thread-safe: give each thread its own accumulator.
  void integrate(const Link& link, std::uint64_t seed, CouplingAccumulator& accumulator,
                 LinkIntegral& result, std::size_t trial = 0) const;
  LinkIntegral integrate(const Link& link, std::uint64_t seed = 0, std::size_t trial = 0) const;

 private:
  void integrateSamples(const Link& link, const RuleSamples& samples,
                        const WeightedBasisTable* receiverBasis,
                        const WeightedBasisTable* sourceBasis, CouplingAccumulator& accumulator,
                        LinkIntegral& result) const;

  // A draw kept with its weighted basis tables (product draws only).
  struct KeptDraw {
    RuleSamples samples;
    WeightedBasisTable receiverBasis, sourceBasis;
  };
  static KeptDraw keep(RuleSamples samples, int degree);

  std::shared_ptr<const Rule> rule_;
  int degree_;
  std::vector<KeptDraw> kept_;  // deterministic rules: one; rules of listed draws: each

};

}  // namespace radquad
