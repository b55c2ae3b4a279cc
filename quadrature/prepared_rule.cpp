#include "quadrature/prepared_rule.h"

#include "kernel/legendre_basis.h"

namespace radquad {

PreparedRule::KeptDraw PreparedRule::keep(RuleSamples samples, int degree) {
  KeptDraw kept;
  kept.samples = std::move(samples);
  if (kept.samples.isProduct) {
    kept.receiverBasis = makeWeightedBasisTable(kept.samples.receiver, degree);
    kept.sourceBasis = makeWeightedBasisTable(kept.samples.source, degree);
  }
  return kept;
}

PreparedRule::PreparedRule(std::shared_ptr<const Rule> rule, int degree)
    : rule_(std::move(rule)), degree_(degree) {
  validateBasisDegree(degree_);
  if (!rule_->isRandom()) {
    kept_.push_back(keep(rule_->samples(0), degree_));
  } else {
    for (std::size_t d = 0; d < rule_->drawCount(); ++d) {
      kept_.push_back(keep(rule_->listedDraw(d), degree_));
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
                             LinkIntegral& result, std::size_t trial) const {
  if (!kept_.empty()) {
    const std::size_t index = rule_->isRandom() ? trial : 0;
    if (index >= kept_.size()) rule_->listedDraw(index);  // throws, naming the rule
    const KeptDraw& draw = kept_[index];
    integrateSamples(link, draw.samples, &draw.receiverBasis, &draw.sourceBasis, accumulator,
                     result);
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

LinkIntegral PreparedRule::integrate(const Link& link, std::uint64_t seed, std::size_t trial) const {
  CouplingAccumulator accumulator;
  LinkIntegral result;
  integrate(link, seed, accumulator, result, trial);
  return result;
}

}  // namespace radquad
