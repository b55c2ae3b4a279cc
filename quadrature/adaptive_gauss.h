// The adaptive choice of Gauss product rules for one link (Gershbein 1995, section 5 and
// Figure 4, "ChooseGaussRules"; docs/design.md, "The solver").
//
// With a degree-d basis, the receiver gets the (d+1)-point Gauss rule on both of its axes
// (nothing is known about the functions it will be projected on). Along each source axis,
// the highest order m whose coefficient magnitude exceeds ErrThres gets the (m+1)-point rule
// (at least 1 point): a source whose high-order coefficients are negligible is essentially a
// polynomial of lower degree along that axis, and the (m+1)-point rule integrates it as well
// as the full rule would wherever the kernel G is smooth. A partially occluded link (G has
// visibility discontinuities) gets one more point on one source axis that has fewer than
// d+1, chosen at random with the link's own generator.
//
// This file knows nothing of scenes or elements: the caller supplies the source's coefficient
// magnitudes already expressed in the units it compares with ErrThres (the solver uses each
// component's RMS radiosity over the element divided by the scene's emitted radiosity; see
// radiosity/README.md, "Adaptive rules").
#pragma once

#include <array>
#include <cstdint>

#include "quadrature/gauss_legendre.h"

namespace radquad {

class PhiloxStream;

// The highest basis degree handled (8-point rules at most, as radiosity/gauss_tables.h).
inline constexpr int kMaxAdaptiveDegree = 7;

struct AdaptiveGaussInput {
  int degree = 0;  // 0 <= d <= kMaxAdaptiveDegree
  // (d+1)^2 magnitudes of the source's coefficients B_(i,j), index i*(d+1) + j with i the
  // order along the source's u axis, each already the largest over colour channels (>= 0).
  const double* magnitudes = nullptr;
  double errThres = 0.0;
  bool partiallyOccluded = false;
};

// The orders' magnitudes along each axis: along u, order i has the largest over j of
// magnitudes[i*(d+1)+j]; along v, order j has the largest over i. Writes d+1 values to each.
void axisMagnitudes(int degree, const double* magnitudes, double* alongU, double* alongV);

// The number of points for one source axis: m + 1, m the highest order (0..orders-1) whose
// magnitude exceeds errThres (strictly), or 1 when none does.
int pointsForAxis(const double* orderMagnitudes, int orders, double errThres);

// Figure 4 without its last step (the variant `adaptive-novis`).
GaussPointCounts chooseGaussRulesNoVisibility(const AdaptiveGaussInput& input);

// Figure 4: as above, then, for a partially occluded link, one source axis with fewer than
// d+1 points gets one more; when both qualify, `generator` picks one (one draw of
// generator.bounded(2): 0 is u, 1 is v). No draw is made otherwise.
GaussPointCounts chooseGaussRules(const AdaptiveGaussInput& input, PhiloxStream& generator);

// Figure 4's last step alone ("RandomlyIncreaseAnAxis"), on a partially occluded link's rule
// without it: one source axis with fewer than d+1 points gets one more, `generator` choosing
// when both qualify (as above). chooseGaussRules is chooseGaussRulesNoVisibility followed by
// this for a partially occluded link.
GaussPointCounts increaseAnAxis(GaussPointCounts rule, int degree, PhiloxStream& generator);

// The seed of a link's own generator, a pure function of the link's identity (its receiver
// and source element ids), so that the choice does not depend on the order links are
// visited in or on the thread count: deriveSeed(baseSeed, {receiver, source})
// (quadrature/random/seeds.h).
std::uint64_t linkSeed(std::uint64_t baseSeed, std::uint32_t receiver, std::uint32_t source);

// The kernel evaluations of one product rule: Rs Rt Su Sv.
inline std::uint64_t ruleEvaluations(const GaussPointCounts& rule) {
  return std::uint64_t(rule[0]) * std::uint64_t(rule[1]) * std::uint64_t(rule[2]) *
         std::uint64_t(rule[3]);
}

}  // namespace radquad
