// The orthonormal tensor Legendre basis of docs/design.md, "Conventions":
//   phi_k(t) = sqrt(2k+1) P_k(2t-1) on [0,1] (shifted Legendre, orthonormal in L2[0,1]),
//   M_(i,j)(u,v) = phi_i(u) phi_j(v) / sqrt(A), index a = i*(d+1) + j, i along edge_u.
// The 1/sqrt(A) factor is applied by the coupling code; the functions here work on the
// unit square.
#pragma once

#include <cstddef>

namespace radquad {

inline constexpr int kMaxBasisDegree = 8;

// Throws InputError unless 0 <= degree <= kMaxBasisDegree.
void validateBasisDegree(int degree);

// Number of tensor basis functions (d+1)^2 of degree d.
inline constexpr int basisFunctionCount(int degree) {
  return (degree + 1) * (degree + 1);
}

// Writes phi_0(t) .. phi_order(t) to values[0..order].
void shiftedLegendreValues(int order, double t, double* values);

// Writes the (d+1)^2 values phi_i(u) phi_j(v) at index i*(d+1)+j.
void tensorBasisValues(int degree, double u, double v, double* values);

// c_k = int_0^1 |phi_k(t)| dt, used by the L1 error bound of Figure 2 (docs/design.md, "The study").
double legendreAbsoluteIntegral(int order);

}  // namespace radquad
