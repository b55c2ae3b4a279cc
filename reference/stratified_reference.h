// The paper's reference and its own error (Gershbein 1995, section 4: "10,000 point
// stratified Monte Carlo method (10 stratified zones in each dimension)").
//
// The reference value is one draw of the rule `Reference` (= Stratified:10) with the given
// seed. Its standard error is estimated from independent replicates: R draws of the same
// rule with seeds replicateSeed(seed, 0..R-1) (replicate 0 is the reported draw itself); the
// sample standard deviation of the R draws, entry by entry, estimates the standard
// deviation of one draw, which is the standard error of the reported value. This makes no
// assumption about the integrand (smooth or cut by shadows), unlike collapsed-strata
// estimators, which overstate the error of smooth integrands. With R = 10 the estimate of
// the standard error itself is uncertain by about 1/sqrt(2(R-1)) = 24% (chi-square with
// R-1 degrees of freedom). reference/README.md states the method and its calibration test.
//
// Options (ReferenceOptions):
// | field          | default | meaning                                            |
// |----------------|---------|----------------------------------------------------|
// | strataPerAxis  | 10      | k of Stratified:k (the paper's reference: 10)      |
// | replicates     | 10      | R, independent draws for the standard error (>= 2) |
#pragma once

#include <Eigen/Core>
#include <cstdint>

#include "kernel/coupling.h"

namespace radquad {

struct ReferenceOptions {
  int strataPerAxis = 10;
  int replicates = 10;
};

struct ReferenceEstimate {
  LinkIntegral integral;                  // the reported draw (replicate 0, seed `seed`)
  Eigen::MatrixXd couplingStandardError;  // entrywise, same shape as the coupling
  double formFactorStandardError = 0.0;
  int replicates = 0;
  std::uint64_t totalKernelEvaluations = 0;  // over all replicates
};

// Throws InputError when the options are out of range.
ReferenceEstimate stratifiedReference(const Link& link, int degree, std::uint64_t seed,
                                      const ReferenceOptions& options = {});

// Mean and standard error of the mean of R independent draws of Stratified:k with seeds
// replicateSeed(seed, firstIndex + j); used by the dense gold reference of occluded links.
struct ReplicateMean {
  Eigen::MatrixXd coupling, couplingStandardError;
  double formFactor = 0.0, formFactorStandardError = 0.0;
  std::uint64_t kernelEvaluations = 0;
  std::uint64_t raysCast = 0, raysBlocked = 0;
};
ReplicateMean stratifiedReplicateMean(const Link& link, int degree, std::uint64_t seed,
                                      int strataPerAxis, int replicates, std::uint32_t firstIndex);

}  // namespace radquad
