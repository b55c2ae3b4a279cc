// How far a one-point Gauss rule along one source axis is from the kernel's integral along it.
//
// The adaptive rules (Gershbein 1995, Figure 4) give a source axis fewer points when the
// source's radiosity is nearly a polynomial of lower degree along it. Their argument bounds
// the error from the radiosity only: it assumes the kernel G is smooth over the source. With
// two or more points the rule still integrates a kernel whose variation is quadratic (or
// more) exactly against the kept orders; with one point it is the midpoint rule, whose error,
//   int_{-h/2}^{h/2} g - h g(0) = h^3 g''/24 + O(h^5),
// has the sign of g'' wherever the kernel is peaked or bowed, and so adds up over a
// receiver's links instead of cancelling: on cornell at degree 2 the report's choice alone
// left the block faces 2-3% brighter than the fixed rules, while the solution's global L2
// difference was 0.2%.
//
// The estimate: with g0 = G(x, c) at the receiver's centre x and the source's centre c, and
// g+-, G at the midpoints of the source's two edges across the axis (c +- e/2),
// Simpson's rule over the axis, h (g- + 4 g0 + g+) / 6, is exact to the cubic, and the
// midpoint rule's relative error is estimated as their difference over the midpoint value:
//   |g+ + g- - 2 g0| / (6 g0).
// G is the unoccluded kernel with clamped cosines (unoccludedKernel, kernel/coupling.h; the
// estimate is a ratio, so its 1/pi does not matter); where g0 = 0 and either g+- is not (the
// source's centre lies behind the receiver's plane or the other way round) the estimate is
// 1: a one-point rule there sees nothing of a link that carries energy.
#pragma once

#include "kernel/patch.h"

namespace radquad {

// The estimated relative error of the one-point rule along the source's u axis (alongU) or
// v axis, seen from the receiver's centre (above). Three kernel evaluations.
double midpointRelativeError(const Patch& receiver, const Patch& source, bool alongU);

}  // namespace radquad
