// The Rule interface: a quadrature rule on [0,1]^4 with coordinates (s, t, u, v) =
// (receiver u, receiver v, source u, source v) and weights summing to 1 (docs/design.md).
//
// A rule is data with a name, a sample count, a declared polynomial degree (none for random
// rules) and a citation. Product rules keep their structure: they hand out a receiver point
// set and a source point set, and the kernel is evaluated on every pair, so the coupling
// code can share positions and basis values. Other rules hand out a list of 4D points.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>

#include "kernel/sample_points.h"

namespace radquad {

// One draw of a rule's points. Deterministic rules return the same draw for every seed.
struct RuleSamples {
  bool isProduct = false;
  PatchSamples receiver;  // product rules: points on the receiver's parameter square
  PatchSamples source;    // product rules: points on the source's parameter square
  LinkSamples points;     // other rules: points on [0,1]^4

  std::size_t size() const { return isProduct ? receiver.size() * source.size() : points.size(); }
};

// A draw's points as one 4D list: a product's every (receiver point, source point) pair with
// the product of their weights, in the product path's pair order (receiver-major).
LinkSamples flattenedPoints(const RuleSamples& samples);

class Rule {
 public:
  virtual ~Rule() = default;

  // The name users type, as in docs/design.md, "The kernel and the rules" (e.g. "FullGauss", "Gauss:3x3x2x2").
  virtual std::string name() const = 0;
  // Kernel evaluations per link.
  virtual std::size_t sampleCount() const = 0;
  // The total polynomial degree on [0,1]^4 integrated exactly, and not the next one; none for
  // random rules.
  virtual std::optional<int> degree() const = 0;
  // The family (e.g. "Gauss-Legendre product", "Stroud", "Monte Carlo").
  virtual std::string family() const = 0;
  // Where the rule comes from.
  virtual std::string citation() const = 0;
  // Whether the points depend on the seed.
  virtual bool isRandom() const { return false; }

  // The points for one trial. Random rules must give the same points for the same seed on
  // every machine and thread count. Rules given as a list of draws (below) give draw 0.
  virtual RuleSamples samples(std::uint64_t seed) const = 0;
  // Random rules given as a list of draws rather than by a seed (rule files with "draws",
  // Python callables): trial t uses draw t, whatever the seed. How many draws such a rule
  // lists; 0 for every other rule.
  virtual std::size_t drawCount() const { return 0; }
  // Draw `trial` (< drawCount()) of such a rule.
  virtual const RuleSamples& listedDraw(std::size_t trial) const;
  // The same points written into `out`, reusing its storage (the hot path of random rules).
  virtual void drawSamples(std::uint64_t seed, RuleSamples& out) const { out = samples(seed); }
  // The same points, block by block, for rules of equal weights that can produce any range of
  // their points on its own; null for the others. PreparedRule integrates through it.
  virtual std::unique_ptr<PointStream> pointStream(std::uint64_t) const { return nullptr; }

  std::string toString() const;
};

// InputError naming the rule when it lists fewer draws than the `trials` asked of it (`where`:
// the option or config that asks).
void checkDrawCount(const Rule& rule, int trials, const std::string& where);

}  // namespace radquad
