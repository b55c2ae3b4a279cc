#include "reference/stratified_reference.h"

#include <memory>
#include <string>

#include "kernel/input_error.h"
#include "quadrature/estimate.h"
#include "quadrature/prepared_rule.h"
#include "quadrature/random/seeds.h"
#include "quadrature/rules/stratified.h"

namespace radquad {
namespace {

// R independent draws of Stratified:k (seeds replicateSeed(seed, firstIndex + j)), summarised
// one at a time by EntrywiseMoments; `first` receives draw 0.
struct Draws {
  LinkIntegral first;
  EntrywiseMoments coupling, formFactor;
  std::uint64_t kernelEvaluations = 0, raysCast = 0, raysBlocked = 0;
};

Draws drawReplicates(const Link& link, int degree, std::uint64_t seed, int strataPerAxis,
                     int replicates, std::uint32_t firstIndex) {
  if (strataPerAxis < 1 || strataPerAxis > 56) {
    throw InputError("reference: strata per axis " + std::to_string(strataPerAxis) +
                     " is out of range: expected 1..56");
  }
  if (replicates < 2 || replicates > 100000) {
    throw InputError("reference: " + std::to_string(replicates) +
                     " replicates cannot estimate a standard error: expected 2..100000");
  }
  const PreparedRule prepared(std::make_shared<StratifiedRule>(strataPerAxis), degree);
  CouplingAccumulator accumulator;
  Draws draws;
  LinkIntegral integral;
  for (int j = 0; j < replicates; ++j) {
    prepared.integrate(link, replicateSeed(seed, firstIndex + std::uint32_t(j)), accumulator,
                       integral);
    if (j == 0) draws.first = integral;
    draws.coupling.add(integral.coupling);
    draws.formFactor.add(integral.formFactor);
    draws.kernelEvaluations += integral.kernelEvaluations;
    draws.raysCast += integral.raysCast;
    draws.raysBlocked += integral.raysBlocked;
  }
  return draws;
}

}  // namespace

ReferenceEstimate stratifiedReference(const Link& link, int degree, std::uint64_t seed,
                                      const ReferenceOptions& options) {
  const Draws draws =
      drawReplicates(link, degree, seed, options.strataPerAxis, options.replicates, 0);
  ReferenceEstimate estimate;
  estimate.integral = draws.first;
  estimate.replicates = options.replicates;
  // The sample standard deviation of one draw is the standard error of the reported draw.
  estimate.couplingStandardError = draws.coupling.sampleDeviation();
  estimate.formFactorStandardError = draws.formFactor.sampleDeviation()(0, 0);
  estimate.totalKernelEvaluations = draws.kernelEvaluations;
  return estimate;
}

ReplicateMean stratifiedReplicateMean(const Link& link, int degree, std::uint64_t seed,
                                      int strataPerAxis, int replicates, std::uint32_t firstIndex) {
  const Draws draws = drawReplicates(link, degree, seed, strataPerAxis, replicates, firstIndex);
  ReplicateMean result;
  result.coupling = draws.coupling.mean();
  result.formFactor = draws.formFactor.mean()(0, 0);
  // The standard error of a mean of R independent draws.
  result.couplingStandardError = draws.coupling.standardError();
  result.formFactorStandardError = draws.formFactor.standardError()(0, 0);
  result.kernelEvaluations = draws.kernelEvaluations;
  result.raysCast = draws.raysCast;
  result.raysBlocked = draws.raysBlocked;
  return result;
}

}  // namespace radquad
