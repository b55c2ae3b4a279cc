// Quadrature points handed to the kernel. The kernel knows no rule: it integrates whatever
// weighted points it is given (weights sum to 1 over the unit square or the unit 4-cube;
// docs/design.md, "Conventions").
#pragma once

#include <cstddef>
#include <vector>

namespace radquad {

// Points (u,v) on one patch's parameter square with weights; the two halves of a product rule.
struct PatchSamples {
  std::vector<double> u, v, weight;

  std::size_t size() const { return u.size(); }
  void push(double pu, double pv, double w) {
    u.push_back(pu);
    v.push_back(pv);
    weight.push_back(w);
  }
};

// Points (s,t,u,v) on [0,1]^4 = (receiver u, receiver v, source u, source v) with weights.
struct LinkSamples {
  std::vector<double> s, t, u, v, weight;

  std::size_t size() const { return s.size(); }
  void push(double ps, double pt, double pu, double pv, double w) {
    s.push_back(ps);
    t.push_back(pt);
    u.push_back(pu);
    v.push_back(pv);
    weight.push_back(w);
  }
};

// A 4D point set of equal weights 1/size(), produced block by block on request, so that a
// large random rule (the 10,000-point reference) is integrated without storing its points
// (CouplingAccumulator::streamed). The points are those of the rule's samples(seed), in the
// same order.
class PointStream {
 public:
  virtual ~PointStream() = default;
  virtual std::size_t size() const = 0;
  // Writes points first .. first + count - 1 (first + count <= size()) to s, t, u, v.
  virtual void fill(std::size_t first, std::size_t count, double* s, double* t, double* u,
                    double* v) const = 0;
};

}  // namespace radquad
