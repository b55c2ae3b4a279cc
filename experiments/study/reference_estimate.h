// The reference the study's errors are measured against (DESIGN.md, "The study"): by
// default the paper's `Reference` rule (10,000 stratified samples), with its own estimated
// standard error per coefficient when the rule provides one.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <memory>
#include <string>

#include "kernel/coupling.h"
#include "quadrature/prepared_rule.h"

namespace radquad {

struct ReferenceResult {
  LinkIntegral integral;
  Eigen::MatrixXd standardError;  // same shape as the coupling; empty when not estimated
};

class ReferenceEstimator {
 public:
  ReferenceEstimator(const std::string& ruleName, int degree);

  const Rule& rule() const { return prepared_.rule(); }
  // How the standard error is estimated ("none" when it is not).
  std::string standardErrorMethod() const;

  // Thread-safe: give each thread its own accumulator.
  void estimate(const Link& link, std::uint64_t seed, CouplingAccumulator& accumulator,
                ReferenceResult& result) const;

 private:
  PreparedRule prepared_;
};

}  // namespace radquad
