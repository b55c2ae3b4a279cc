// The references the study's errors are measured against (docs/design.md, "The study"):
// - the paper's reference, Stratified:k with k = 10 (10,000 samples), with its own standard
//   error from independent replicates (reference/stratified_reference.h);
// - on request, the gold reference (reference/gold_reference.h).
// A partial candidate is classified by the visible fraction of the reference's own rays
// (its reported draw) before the replicates are spent on it.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>

#include "kernel/coupling.h"
#include "quadrature/prepared_rule.h"
#include "reference/gold_reference.h"
#include "reference/stratified_reference.h"

namespace radquad {

struct ReferenceResult {
  LinkIntegral integral;
  Eigen::MatrixXd standardError;  // same shape as the coupling
};

class ReferenceEstimator {
 public:
  ReferenceEstimator(const ReferenceOptions& options, int degree);

  const Rule& rule() const { return draw_.rule(); }
  std::string name() const;
  std::size_t samples() const { return draw_.rule().sampleCount(); }

  // The reported draw alone (the rays that classify a candidate). Thread-safe.
  void draw(const Link& link, std::uint64_t seed, CouplingAccumulator& accumulator,
            LinkIntegral& result) const;
  // The reported draw (as given by draw()) and its standard error from the replicates: the
  // estimator of stratifiedReference (reference/stratified_reference.h), replicate j drawn
  // with replicateSeed(seed, j), computed here with the caller's scratch so that thousands of
  // links allocate nothing. Thread-safe.
  ReferenceResult estimate(const Link& link, std::uint64_t seed, const LinkIntegral& reportedDraw,
                           CouplingAccumulator& accumulator) const;

 private:
  ReferenceOptions options_;
  int degree_;
  PreparedRule draw_;
};

ReferenceOptions parseReferenceOptions(const nlohmann::json& value, const std::string& where);
nlohmann::json referenceOptionsToJson(const ReferenceOptions& options);
// The study's gold (docs/design.md, "The gold"): the exact gold to 3e-4 of K's largest entry,
// the soups' dense stratified gold on 16^4 strata x 8 replicates. Enough for the noise check
// (the gold's own mean error under 1% of every rule's, study_metrics.h): the full suites'
// worst share is 0.3%, carried by the soups' dense golds, not by the exact ones (docs/study.md,
// "The gold": why 3e-4).
GoldOptions studyGoldOptions();
// A config's "gold" object; keys it leaves out take studyGoldOptions().
GoldOptions parseGoldOptions(const nlohmann::json& value, const std::string& where);
nlohmann::json goldOptionsToJson(const GoldOptions& options);

}  // namespace radquad
