// A rule bound to a basis degree, ready to integrate many links. Deterministic rules keep
// their points and weighted basis tables, built once; random rules draw their points from
// the seed of each call.
#pragma once

#include <cstdint>
#include <memory>

#include "kernel/coupling.h"
#include "quadrature/rule.h"

namespace radquad {

class PreparedRule {
 public:
  PreparedRule(std::shared_ptr<const Rule> rule, int degree);

  const Rule& rule() const { return *rule_; }
  int degree() const { return degree_; }

  // Integrates the coupling of one link. Thread-safe: give each thread its own accumulator.
  void integrate(const Link& link, std::uint64_t seed, CouplingAccumulator& accumulator,
                 LinkIntegral& result) const;
  LinkIntegral integrate(const Link& link, std::uint64_t seed = 0) const;

 private:
  void integrateSamples(const Link& link, const RuleSamples& samples,
                        const WeightedBasisTable* receiverBasis,
                        const WeightedBasisTable* sourceBasis, CouplingAccumulator& accumulator,
                        LinkIntegral& result) const;

  std::shared_ptr<const Rule> rule_;
  int degree_;
  RuleSamples fixedSamples_;  // deterministic rules only
  WeightedBasisTable receiverBasis_, sourceBasis_;
};

}  // namespace radquad
