// Rules given as data (points and weights) rather than code: what `File:PATH` rules and
// `radquad rules --dump` exchange (experiments/rule_file.h has the file format).
//
// A data rule is a product of a receiver and a source point set (kept as a product, so the
// coupling code's fast path is used) or a list of 4D points. It is deterministic (one draw),
// or random, given as a list of draws: trial t of a study or of `radquad link --trials` uses
// draw t (Rule::listedDraw), so a rule drawn by any outside generator is scored as the built-in
// random rules are. Every draw has the same form and the same number of points. It is checked
// when it is made: every coordinate in [0, 1], every value finite, weights summing to 1, and,
// when a degree is declared (deterministic rules only), exactness for every polynomial of
// total degree up to it (the tensor Legendre polynomials, as the registry's own rules are
// tested).
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "quadrature/rule.h"

namespace radquad {

// The highest degree a data rule may declare (its check walks every tensor Legendre
// polynomial up to it: C(D + 4, 4) of them, 46,376 at 30).
inline constexpr int kMaxDataRuleDegree = 30;

struct DataRuleSpec {
  std::string name;
  std::optional<int> degree;  // total degree integrated exactly; none: not claimed
  std::string citation;
  bool random = false;             // a list of draws, one per trial
  std::vector<RuleSamples> draws;  // one for a deterministic rule
};

class DataRule : public Rule {
 public:
  std::string name() const override { return spec_.name; }
  std::size_t sampleCount() const override;
  std::optional<int> degree() const override { return spec_.degree; }
  std::string family() const override { return "data"; }
  std::string citation() const override { return spec_.citation; }
  bool isRandom() const override { return spec_.random; }
  RuleSamples samples(std::uint64_t seed) const override;
  std::size_t drawCount() const override { return spec_.random ? spec_.draws.size() : 0; }
  const RuleSamples& listedDraw(std::size_t trial) const override;

 private:
  friend std::shared_ptr<const Rule> makeDataRule(DataRuleSpec spec, const std::string& where);
  explicit DataRule(DataRuleSpec spec) : spec_(std::move(spec)) {}
  DataRuleSpec spec_;
};

// Checks `spec` (above) and makes the rule; InputError naming `where` and the failed check
// otherwise.
std::shared_ptr<const Rule> makeDataRule(DataRuleSpec spec, const std::string& where);

// The largest error of `points` over the tensor Legendre polynomials
// phi_a(s) phi_b(t) phi_c(u) phi_e(v) of total degree exactly `degree` (their integrals are 1
// for the constant and 0 otherwise).
double legendreExactnessError(const LinkSamples& points, int degree);

// The highest total degree `points` integrate exactly, checking degrees 0, 1, ... up to `cap`:
// exact at a degree when every tensor Legendre polynomial of it is within 1e-10 of the sum of
// |w| (the check of declared degrees, here and in the registry's rules). Returns `cap` when
// every degree up to it holds; otherwise one less than the first failing degree, whose
// largest error goes to `failingError`.
int exactnessDegree(const LinkSamples& points, int cap, double& failingError);

}  // namespace radquad
