// Gauss-Legendre nodes and weights for any number of points n >= 1, computed by Newton's
// method on P_n in long double (nodes: the zeros of P_n; weights 2 / ((1 - x^2) P_n'(x)^2);
// Abramowitz and Stegun 1964, 25.4.29). An n-point rule integrates polynomials of degree
// 2n - 1 exactly, and not degree 2n.
#pragma once

#include <array>
#include <vector>

#include "kernel/sample_points.h"

namespace radquad {

inline constexpr int kMaxGaussPoints = 64;

struct GaussLegendreRule {
  std::vector<double> nodes;    // ascending
  std::vector<double> weights;  // summing to the interval's length
};

// On [-1,1]. Throws InputError unless 1 <= n <= kMaxGaussPoints.
GaussLegendreRule gaussLegendre(int n);
// Mapped to [0,1]: nodes (1 + x) / 2, weights w / 2 (summing to 1). Cached.
const GaussLegendreRule& gaussLegendreUnit(int n);

// Gauss-Legendre points per axis of a product rule on [0,1]^4, in the rules' axis order
// {Rs, Rt, Su, Sv} = (receiver u, receiver v, source u, source v).
struct GaussPointCounts : std::array<int, 4> {};

// The product of the unit rules of `alongU` and `alongV` points on a parameter square, u-major
// (point i * alongV + j at (node_i, node_j), weight w_i w_j): the one source of the Gauss
// product point sets, for the Gauss rules (quadrature/rules/gauss_product.h) and the solver's
// tables (radiosity/gauss_tables.h).
PatchSamples gaussProductSamples(int alongU, int alongV);

}  // namespace radquad
