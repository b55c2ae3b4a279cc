// The JSON objects `radquad link` and `radquad reference` print, for a link given as a
// LinkGeometry: shared by the command line and the Python module (python/), so that both
// give the same numbers, bit for bit.
#pragma once

#include <cstdint>
#include <memory>
#include <nlohmann/json.hpp>
#include <ostream>
#include <string>

#include "experiments/json_input.h"
#include "quadrature/rule.h"
#include "reference/gold_reference.h"

namespace radquad {

struct LinkReportOptions {
  int degree = 0;
  std::uint64_t seed = 0;
  int trials = 1;  // random rules: trials with seeds seed .. seed + trials - 1
};

// `radquad link`'s object: rule, samples, rule_degree, degree, seed, kernel_evaluations,
// form_factor, coupling, visible_fraction, rays_cast; `warnings` (near-singular link, form
// factor outside [0, 1]) when there are any; with trials > 1, the trials' statistics.
// Warnings, and a deterministic rule's ignored trials, are also written to `log` when given.
// InputError when the seeds would pass 2^64 - 1; ComputationError on a non-finite coupling
// (`where` names the link in messages).
nlohmann::json linkReport(const LinkGeometry& description,
                          const std::shared_ptr<const Rule>& rule,
                          const LinkReportOptions& options, const std::string& where,
                          std::ostream* log);

struct ReferenceReportOptions {
  int degree = 0;
  std::uint64_t seed = 0;
  int replicates = 10;
  bool gold = false;
  GoldOptions goldOptions;  // its exactTolerance and method are the command's
};

// `radquad reference`'s object (`link` is what it names the link): the paper's reference
// with its standard error (`standard_error.reliable` false on a near-singular link, where
// the kernel's variance is unbounded), and with options.gold the gold and
// reference_minus_gold; `warnings` (near-singular link, form factor outside [0, 1], the
// reference more than 5 standard errors from the gold) when there are any, also written to
// `log` when given.
nlohmann::json referenceReport(const LinkGeometry& description,
                               const ReferenceReportOptions& options, const std::string& link,
                               std::ostream* log = nullptr);

// A gold reference as `reference --gold` reports it.
nlohmann::json goldToJson(const GoldReference& gold, const GoldOptions& options);

}  // namespace radquad
