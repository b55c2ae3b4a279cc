// The solver's rule choice (Gershbein 1995, Figure 4, and the fixed rules): each link's Gauss
// points per axis, chosen from its source's coefficients and grown, never shrunk, as the
// solution changes; refinement.cpp refines, solver.cpp integrates and iterates, gather.cpp
// gathers.
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

#include "quadrature/adaptive_gauss.h"
#include "quadrature/random/philox.h"
#include "radiosity/gauss_tables.h"
#include "radiosity/kernel_curvature.h"
#include "radiosity/link_integration.h"
#include "radiosity/solver.h"
#include "radiosity/solver_impl.h"

namespace radquad {

const char* ruleChoiceName(RuleChoice rules) {
  switch (rules) {
    case RuleChoice::kFixed:
      return "fixed";
    case RuleChoice::kAdaptive:
      return "adaptive";
    case RuleChoice::kAdaptiveNoVisibility:
      return "adaptive-novis";
  }
  return "?";
}

// Fixed: (d+1)^4. Adaptive (Gershbein 1995, Figure 4): the source's coefficient magnitudes
// are each component's RMS radiosity over the element, |B_(i,j),c| / sqrt(A_S) (the basis is
// orthonormal over the element, so int (B M)^2 dA = B^2), largest over channels c, divided by
// the scene's radiosity scale: ErrThres is then a fraction of the scene's mean emitted
// radiosity, independent of scene units and element size. A link's rule only grows: the
// report re-checks couplings after each iteration "to see if we need a better quadrature rule
// due to the energy gain"; a rule never shrinks back (that would only recompute to lose
// accuracy). The partial-visibility draw uses a generator keyed by the (receiver, source)
// element ids, so it is the same whatever the thread count.
AdaptiveGaussInput Solver::adaptiveInput(int sourceElement, double* magnitudes) const {
  const int n = options_.degree + 1;
  const Element& source = (*hierarchy_)[sourceElement];
  const double normaliser =
      radiosityScale_ > 0.0 ? 1.0 / (std::sqrt(source.geometry.area) * radiosityScale_) : 0.0;
  for (int a = 0; a < n * n; ++a) {
    magnitudes[a] = source.radiosity.row(a).cwiseAbs().maxCoeff() * normaliser;
  }
  AdaptiveGaussInput input;
  input.degree = options_.degree;
  input.magnitudes = magnitudes;
  input.errThres = options_.errThres;
  return input;
}

namespace {

// A rule's points along one side of an element, for `points` chosen per axis of a square
// (d+1 for fixed rules, Figure 4's choice for the adaptive ones): along a side r times
// longer than the other, `points` round(r) (at most GaussTables::kMaxPointsPerAxis), so that
// the points are about as far apart along both sides. The quadtree keeps an element's shape
// at every level (a 13:1 slat stays 13:1), and with d+1 points along its length its
// couplings missed the kernel's variation there (the slats scene at degree 0 converged 5% off
// on average).
int alongSide(const Patch& element, bool alongU, int points) {
  const double lengthU = element.edgeU.norm(), lengthV = element.edgeV.norm();
  const double ratio = alongU ? lengthU / lengthV : lengthV / lengthU;
  return std::min(GaussTables::kMaxPointsPerAxis, points * std::max(1, int(std::lround(ratio))));
}

}  // namespace

GaussPointCounts Solver::chooseRule(const SolverLink& link,
                                      std::uint64_t* checkEvaluations) const {
  const int n = options_.degree + 1;
  // Fixed rules: d+1 points per axis, but 2 at degree 0, where the midpoint rule overestimates
  // peaked kernels and bright scenes create energy, and 3 where the elements are moderately
  // near (link_integration.h), where 2 points underestimate the kernel and a whole scene
  // darkens (radiosity/README.md, "Couplings").
  const Patch& r = (*hierarchy_)[link.receiver].geometry;
  const Patch& s = (*hierarchy_)[link.source].geometry;
  const int fixed = std::max(n, separationRatio(r, s) < kModeratelyNearFactor ? 3 : 2);
  GaussPointCounts rule = {fixed, fixed, fixed, fixed};
  if (options_.rules != RuleChoice::kFixed) {
    // Figure 4 from the source's points of this pass (updateSourcePoints, copied to
    // link.coupling.sourcePoints by computeCouplings), then its visibility step.
    rule = {n, n, link.coupling.sourcePoints[0], link.coupling.sourcePoints[1]};
    if (options_.rules == RuleChoice::kAdaptive && link.visibility == LinkClass::kPartial) {
      PhiloxStream generator(
          linkSeed(options_.seed, std::uint32_t(link.receiver), std::uint32_t(link.source)), 0);
      rule = increaseAnAxis(rule, options_.degree, generator);
    }
  }
  // The receiver keeps the fixed rule's points (Figure 4 gives it d+1; at degree 0 the floor
  // of 2 keeps the midpoint rule's bias away, as for the fixed rules).
  rule[0] = std::max(rule[0], fixed);
  rule[1] = std::max(rule[1], fixed);
  rule = {alongSide(r, true, rule[0]), alongSide(r, false, rule[1]), alongSide(s, true, rule[2]),
          alongSide(s, false, rule[3])};
  // The kernel check (kernel_curvature.h): Figure 4 bounds the error of a reduced rule from
  // the source's radiosity alone; a source axis left with one point is the midpoint rule
  // along it, biased wherever the kernel bows, so it gets a second point there.
  if (options_.rules != RuleChoice::kFixed && options_.kernelCurvature > 0.0) {
    for (int axis = 0; axis < 2; ++axis) {
      if (rule[2 + axis] != 1) continue;
      *checkEvaluations += 3;
      if (midpointRelativeError(r, s, axis == 0) > options_.kernelCurvature) rule[2 + axis] = 2;
    }
  }
  if (link.coupling.computed) {
    for (int axis = 0; axis < 4; ++axis) rule[axis] = std::max(rule[axis], link.coupling.rule[axis]);
  }
  return rule;
}

// The source-axis points {Su, Sv} of Figure 4 without its visibility step, for every element
// (a function of the element's coefficients only). A link whose source's points are those it
// was last integrated with cannot need a larger rule: its visibility step draws from its own
// generator keyed by the link's ids, so it would choose the same rule again. Only the other
// links go through chooseRule, which keeps the per-iteration check at one comparison per link.
void Solver::updateSourcePoints() {
  const int n = options_.degree + 1;
  sourcePoints_.resize(hierarchy_->size());
  tbb::parallel_for(std::size_t(0), hierarchy_->size(), [&](std::size_t e) {
    if (options_.rules == RuleChoice::kFixed) {
      sourcePoints_[e] = {n, n};
      return;
    }
    double magnitudes[(kMaxAdaptiveDegree + 1) * (kMaxAdaptiveDegree + 1)];
    const GaussPointCounts rule = chooseGaussRulesNoVisibility(adaptiveInput(int(e), magnitudes));
    sourcePoints_[e] = {rule[2], rule[3]};
  });
}

}  // namespace radquad
