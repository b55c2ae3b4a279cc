// Stroud's non-product rules for the 4-cube, as studied by Gershbein (1995), section 3.
//
// Citation: A. H. Stroud, "Approximate Calculation of Multiple Integrals", Prentice-Hall,
// 1971: formula Cn 5-7 (after Stroud, "Some fifth degree integration formulas for symmetric
// regions", Math. Comp. 20, 1966, rule "c") and formula Cn 3-1 (after Stroud, "Remarks on
// the disposition of points in numerical integration formulas", MTAC 11, 1957).
//
// Both are stated on [-1,1]^n with weights normalised to sum to 1 and are mapped affinely to
// [0,1]^4 with coordinates (s, t, u, v) (docs/design.md, "The kernel and the rules").
//
// | name         | samples | degree | definition                                             |
// |--------------|---------|--------|--------------------------------------------------------|
// | `Stroud65`   | 65      | 5      | Cn 5-7, n = 4                                          |
// | `HierStroud` | 32      | 3      | Cn 3-1 (n = 4, 8 points) on each of the 4 boxes made   |
// |              |         |        | by halving the receiver's s and t axes                 |
// No parameters.
#pragma once

#include <memory>

#include "quadrature/rule.h"

namespace radquad {

// Points and weights shared by both rules: a 4D point set on [0,1]^4.
class StroudRule : public Rule {
 public:
  std::string name() const override { return name_; }
  std::size_t sampleCount() const override { return samples_.points.size(); }
  std::optional<int> degree() const override { return degree_; }
  std::string family() const override { return "Stroud"; }
  std::string citation() const override { return citation_; }
  RuleSamples samples(std::uint64_t) const override { return samples_; }

  // Stroud Cn 5-7 for n = 4: 65 points, degree 5.
  static std::shared_ptr<const Rule> cn57();
  // Stroud Cn 3-1 for n = 4 on the 4 receiver quadrants: 32 points, degree 3.
  static std::shared_ptr<const Rule> hierarchicalCn31();

 private:
  StroudRule(std::string name, int degree, std::string citation, LinkSamples points);

  std::string name_;
  int degree_;
  std::string citation_;
  RuleSamples samples_;
};

}  // namespace radquad
