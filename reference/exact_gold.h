// The exact-visibility gold (docs/design.md, "The gold"): a deterministic coupling of
// any link, occluded or not, with an estimate of its absolute error.
//
//   K[a][b] = sqrt(A_r / A_s) int_{[0,1]^2} phi_a(s, t) I_b(x(s, t)) ds dt,
//
// the inner integral I_b (source_moments.h) over the exactly visible part of the source
// (exact_visibility.h), the outer one by globally adaptive cubature over the receiver's unit
// square: the degree-7 Genz-Malik rule with its embedded degree-5 rule as the error estimate
// (hcubature from libcubature), bisecting the region of largest error until the estimated
// error of every coefficient is at most `tolerance` times K's largest entry, or the
// evaluation budget is spent (then converged = false). The integrand is analytic between the
// curves where the visible polygon changes shape (shadow edges and vertices crossing the
// source's edges, or each other); the bisection concentrates on those curves. No random
// numbers: the same link gives the same bits, whatever the number of threads (the points of
// a batch are spread over threads; each value depends on its point only).
#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <cstdint>

#include "kernel/coupling.h"

namespace radquad {

struct ExactGoldOptions {
  double tolerance = 1e-7;             // estimated error / max |K| entry
  std::size_t maxEvaluations = 4000000;  // receiver points, each an exact inner integral
};

struct ExactGold {
  Eigen::MatrixXd coupling;
  Eigen::MatrixXd couplingError;  // estimated absolute error of every entry
  double formFactor = 0.0;
  double formFactorError = 0.0;
  bool converged = false;
  std::uint64_t receiverPoints = 0;   // outer evaluations
  std::uint64_t polygonUnions = 0;    // receiver points whose shadows overlapped
  std::size_t candidateOccluders = 0;  // occluder polygons in the link's shaft
};

ExactGold exactGold(const Link& link, int degree, const ExactGoldOptions& options = {});

}  // namespace radquad
