// The inner integral of the exact gold (docs/design.md, "The gold"): for a receiver
// point x with unit normal n_r and the part V of the source it sees (exact_visibility.h),
//   I_b(x) = int_V cos(theta) cos(theta') / (pi r^2) phi_b(u(y), v(y)) dA(y)
// for every source function b of degree d (phi_b the unit-square tensor Legendre basis).
//
// Degree 0 (phi_0 = 1): Lambert's contour formula over V's rings, exact.
//
// Any degree: with p0 the foot of x on the source's plane, H = |x - p0| and rho, psi polar
// coordinates about p0 in the plane, the kernel is H (a0 + a1 rho) / (pi (rho^2 + H^2)^2)
// (a0 + a1 rho = n_r . (y - x), affine) and phi_b along a ray from p0 is a polynomial in rho.
// Each ring edge (a, b) bounds the signed triangle (p0, a, b); over it, the radial integrals
//   J_m(R, H) = int_0^R rho^m / (rho^2 + H^2)^2 d rho
// are taken in closed form (recurrences in atan and log), or, where R / H is small and the
// recurrences lose digits (below 0.85 for degree <= 3, below 2 above), by a Gauss rule of 12
// (16 above degree 3) points that is exact to rounding there. At degrees 0-3 the edge nodes
// go eight at a time through branch-free loops over the lanes (vector instructions; with GCC
// glibc's vector atan and log1p, within 4 units in the last place), each lane keeping its
// own branch (laneRadialMoments). The angular integral: 12-point Gauss rules along
// the edge on pieces no longer than the distance to the integrand's nearest complex singularity
// (at sqrt(d^2 + H^2) from the edge's closest point to p0, d the distance of the edge's line):
// a geometric refinement towards p0 that keeps the rule's error near rounding (about 1e-14
// relative) however close x is to the source. A looser `accuracy` (1e-6 or more) at degrees
// 1 and 2 takes 8 edge points instead, with an error of at most 2e-7 relative where x's foot
// lies over the source, and the radial recurrences from R / H = 0.15 (an 8-point rule
// below), which lose at most 1.3e-10 relative there. Beside the source and near its plane
// (grazing angles, small moments whose edge terms cancel) the 8 points' error relative to
// x's own moments grows, up to 1.1e-4 at degree 2 (source_moments.cpp), small in absolute
// terms; degree 3, where it reached 2.2e-3 and a grazing link's gold missed its estimate,
// keeps the tight rules. The exact gold asks for a hundredth of its tolerance.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "kernel/patch.h"
#include "quadrature/gauss_legendre.h"
#include "reference/exact_visibility.h"

namespace radquad {

class SourceMoments {
 public:
  // accuracy: the relative error allowed in the degree >= 1 (polar) integrals; below 1e-6 or
  // at degree 3 and above, about 1e-14, otherwise at most 2e-7 (where x's foot lies over the
  // source; see above). Lambert's formula (degree 0) is exact either way.
  SourceMoments(const Patch& source, int degree, double accuracy = 1e-14);

  int functions() const { return functions_; }

  // out[b] = I_b(x) for b < functions(); 0 when V is empty.
  void compute(const Eigen::Vector3d& x, const Eigen::Vector3d& receiverNormal,
               const VisibleRings& visible, double* out) const;

  // The same by the polar method at every degree (degree 0 included): the independent
  // check of Lambert's formula in the tests.
  void computePolar(const Eigen::Vector3d& x, const Eigen::Vector3d& receiverNormal,
                    const VisibleRings& visible, double* out) const;

  // Lambert's formula alone: int_V cos cos / (pi r^2) dA.
  double formFactor(const Eigen::Vector3d& x, const Eigen::Vector3d& receiverNormal,
                    const VisibleRings& visible) const;

 private:
  template <int D>
  void polar(const Eigen::Vector3d& x, const Eigen::Vector3d& receiverNormal,
             const VisibleRings& visible, double* out) const;

  const Patch& source_;
  int degree_;
  int functions_;
  const GaussLegendreRule& edgeRule_;
  bool loose_;  // accuracy 1e-6 or more: the radial recurrences from R / H = 0.15
  Eigen::Vector3d axisX_, axisY_;    // orthonormal frame of the source's plane
  Eigen::Matrix2d toParameters_;     // (xi, eta) offsets -> (u, v) offsets
  Eigen::Matrix2d toPlane_;          // (u, v) -> (xi, eta) from the origin
};

// J_m(R, H) for m = 0..maxPower, written to out[m]. Exposed for tests.
void radialMoments(double R, double H, int maxPower, double* out);

// The eight-lane form the inner integral uses at degrees 0-3 (maxPower = 2d + 2: 2, 4, 6 or
// 8; InputError otherwise): out[m * 8 + k] = J_m(X[k], 1) for the 8 values X[0..7] > 0;
// `loose`: as at an accuracy of 1e-6 or more (the recurrences from X = 0.15, at most 1.3e-10
// relative up to the power 6, 1.2e-8 at the power 8). Exposed for tests.
void laneRadialMoments(const double* X, int maxPower, double* out, bool loose = false);

}  // namespace radquad
