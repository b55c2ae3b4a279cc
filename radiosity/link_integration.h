// Integration of one link's coupling K (docs/design.md): with a Gauss product rule
// {Rs, Rt, Su, Sv} where the elements are apart, or with the exact inner integral of
// near_field.h where they are near each other (nearField).
//
// How far apart is apart: a product rule with n points per axis integrates the kernel of two
// elements whose centres are r apart, with radii (half diagonals) a and b, to a relative error
// that falls like (r / (a + b))^-2n (radiosity/README.md, "Couplings", has it measured).
// Gauss rules underestimate the peaked kernel, so such errors do not cancel: with 2 points
// (the fixed rule at degrees 0 and 1) they darken a whole scene. Links closer than
// kNearFactor (a + b), touching or cut by the other's plane go to the near field; links
// closer than kModeratelyNearFactor (a + b) get at least 3 points per axis
// (Solver::chooseRule).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "kernel/coupling.h"
#include "quadrature/gauss_legendre.h"
#include "radiosity/gauss_tables.h"
#include "radiosity/visibility.h"

namespace radquad {

// Whether a corner of either parallelogram lies on the other (within a relative tolerance).
bool elementsTouch(const Patch& a, const Patch& b);

// The longer diagonal of an element: the largest distance between two of its points.
double diameter(const Patch& p);

// The distance between the elements' centres over the sum of their radii (half the longer
// diagonal of each).
double separationRatio(const Patch& a, const Patch& b);

// A lower bound of the distance between two elements from their planes: for each element,
// the smallest distance to its plane of the other's corners when they all lie on one side of
// it (0 when they straddle it); the larger of the two. Exact for parallel elements that face
// each other across a gap.
double planeGap(const Patch& a, const Patch& b);

inline constexpr double kNearFactor = 1.0;
inline constexpr double kModeratelyNearFactor = 2.0;

// Whether a link between these elements is integrated in the near field (near_field.h): they
// touch, one crosses the other's plane, or their separation ratio is below kNearFactor.
bool nearField(const Patch& receiver, const Patch& source);

// What integrating one link adds to the solver's counts.
struct LinkIntegrationCounts {
  std::uint64_t kernelEvaluations = 0;
  std::uint64_t raysCast = 0;
};

// Integrates links with Gauss product rules; one per thread (it keeps scratch space, so a
// warm integrator allocates nothing beyond the output's first sizing).
class LinkIntegrator {
 public:
  // Writes the link's coupling (rows receiver, columns source functions) for `rule`
  // {Rs, Rt, Su, Sv} from `tables`.
  LinkIntegrationCounts integrate(const Link& link, const GaussPointCounts& rule,
                                  const GaussTables& tables, Eigen::Map<Eigen::MatrixXd> coupling);

 private:
  CouplingAccumulator accumulator_;
  LinkIntegral piece_;
};

}  // namespace radquad
