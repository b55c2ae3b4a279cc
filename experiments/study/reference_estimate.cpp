#include "experiments/study/reference_estimate.h"

#include "quadrature/registry.h"

namespace radquad {

ReferenceEstimator::ReferenceEstimator(const std::string& ruleName, int degree)
    : prepared_(findRule(ruleName), degree) {}

std::string ReferenceEstimator::standardErrorMethod() const {
  return "none";
}

void ReferenceEstimator::estimate(const Link& link, std::uint64_t seed,
                                  CouplingAccumulator& accumulator, ReferenceResult& result) const {
  prepared_.integrate(link, seed, accumulator, result.integral);
  result.standardError.resize(0, 0);
}

}  // namespace radquad
