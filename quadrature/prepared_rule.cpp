#include "quadrature/prepared_rule.h"

#include "kernel/legendre_basis.h"

namespace radquad {

PreparedRule::PreparedRule(std::shared_ptr<const Rule> rule, int degree)
    : rule_(std::move(rule)), degree_(degree) {
  validateBasisDegree(degree_);
  if (!rule_->isRandom()) {
    fixedSamples_ = rule_->samples(0);
    if (fixedSamples_.isProduct) {
      receiverBasis_ = makeWeightedBasisTable(fixedSamples_.receiver, degree_);
      sourceBasis_ = makeWeightedBasisTable(fixedSamples_.source, degree_);
    }
  }
}

void PreparedRule::integrateSamples(const Link& link, const RuleSamples& samples,
                                    const WeightedBasisTable* receiverBasis,
                                    const WeightedBasisTable* sourceBasis,
                                    CouplingAccumulator& accumulator, LinkIntegral& result) const {
  if (samples.isProduct) {
    accumulator.product(link, samples.receiver, *receiverBasis, samples.source, *sourceBasis,
                        result);
  } else {
    accumulator.scattered(link, samples.points, degree_, result);
  }
}

void PreparedRule::integrate(const Link& link, std::uint64_t seed, CouplingAccumulator& accumulator,
                             LinkIntegral& result) const {
  if (!rule_->isRandom()) {
    integrateSamples(link, fixedSamples_, &receiverBasis_, &sourceBasis_, accumulator, result);
    return;
  }
  // Rules that stream their points (Stratified:k, the reference) are integrated block by
  // block without storing them.
  if (const auto stream = rule_->pointStream(seed)) {
    accumulator.streamed(link, *stream, degree_, result);
    return;
  }
  // Per-thread storage for the drawn points: allocates nothing once warm.
  thread_local RuleSamples drawn;
  rule_->drawSamples(seed, drawn);
  if (drawn.isProduct) {
    const WeightedBasisTable receiverBasis = makeWeightedBasisTable(drawn.receiver, degree_);
    const WeightedBasisTable sourceBasis = makeWeightedBasisTable(drawn.source, degree_);
    integrateSamples(link, drawn, &receiverBasis, &sourceBasis, accumulator, result);
  } else {
    integrateSamples(link, drawn, nullptr, nullptr, accumulator, result);
  }
}

LinkIntegral PreparedRule::integrate(const Link& link, std::uint64_t seed) const {
  CouplingAccumulator accumulator;
  LinkIntegral result;
  integrate(link, seed, accumulator, result);
  return result;
}

}  // namespace radquad
