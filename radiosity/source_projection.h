// Gathering through a product rule's source points: the coupling of a Gauss product rule with
// pu x pv points on the source keeps only pu x pv source functions' worth of information,
// so the solver stores those columns and gathers against pu x pv values derived from the
// source's radiosity instead of all F columns against all F coefficients.
//
// Along one source axis, let the rule have S <= d+1 Gauss points x_i, weights w_i, and let
// phi_0..phi_d be the orthonormal shifted Legendre functions. The coupling's columns are
// K[:, b] = sum_q A[:, q] w_q phi_b(q) (A the receiver-contracted kernel at source point q),
// so every column is a combination of the point columns. For the orders p < S the S x S
// matrix (phi_p(x_i)) satisfies sum_i w_i phi_p(x_i) phi_p'(x_i) = delta_pp' (the rule is
// exact to degree 2S - 1 >= p + p'), hence it is invertible and
//   K B = sum_{p < S} K[:, p] Bhat_p,   Bhat_p = sum_p' M_S[p][p'] B_p',
//   M_S[p][p'] = sum_i w_i phi_p(x_i) phi_p'(x_i)   (p < S, p' <= d),
// the rule's own projection of the source polynomial on the low orders (M_S[p][p'] =
// delta_pp' for p' < S; the higher orders alias onto them). On the tensor rule this holds
// along each axis, so K B = K_L Bhat with K_L the columns (p, q), p < pu, q < pv, and
// Bhat = (M_pu x M_pv) B. With S = d+1 points, M is the identity and nothing changes.
//
// Two ways to treat the orders p' >= S (DroppedOrders):
// - aliased: Bhat as above, exactly the gather of the whole coupling K computed with the
//   reduced rule for every source function (the report's reading: K for all basis pairs,
//   each with the link's rule). A quadratic seen by one point is its midpoint value, not its
//   mean: B(1/2) = B_0 - (sqrt 5 / 2) B_2, an error of the order of the dropped coefficient
//   with the sign of the source's curvature. Walls darker at the corners than in the middle
//   (every closed room) then gather too much, coherently over all their elements.
// - truncated (the solver's default): M_S[p][p'] = delta_pp', the source taken as its
//   expansion truncated to the orders the rule keeps, which is what the adaptive choice
//   assumes it is ("essentially a polynomial of lower degree along that axis"). The dropped
//   part, orthogonal to every polynomial of degree < S, then gathers int G B_high, which is
//   small where G is smooth instead of the dropped coefficient itself. On cornell at degree 2
//   with the report's choice alone this took the largest per-patch difference to the fixed
//   rules from 2.8% to 1.8% at the same cost.
//
// Both hold for a product rule on the whole source element, partially occluded or not
// (visibility is part of the kernel). Near-field links (near_field.h) integrate the source
// exactly, whatever the rule: they keep every column and gather the whole source.
#pragma once

#include <vector>

namespace radquad {

enum class DroppedOrders { kTruncated, kAliased };

const char* droppedOrdersName(DroppedOrders orders);

class SourceProjection {
 public:
  explicit SourceProjection(int degree, DroppedOrders dropped = DroppedOrders::kTruncated);

  int degree() const { return degree_; }
  DroppedOrders dropped() const { return dropped_; }

  // M_S[p][p'] for S points (1 <= S <= d+1), p < S, p' <= d: the rule's aliasing matrix
  // (aliased) or delta_pp' (truncated).
  double matrix(int points, int p, int pPrime) const;

  // Writes Bhat (pointsU * pointsV rows, index p * pointsV + q, times 3 channels,
  // column-major) of `radiosity` ((d+1)^2 rows, index i * (d+1) + j, times 3, column-major).
  // 1 <= pointsU, pointsV <= d+1.
  void project(int pointsU, int pointsV, const double* radiosity, double* out) const;

  // Keeps the columns (p, q), p < pointsU, q < pointsV, of a (d+1)^2 x (d+1)^2 column-major
  // coupling, moved to the front in the order p * pointsV + q (in place).
  void compact(int pointsU, int pointsV, double* coupling) const;

 private:
  int degree_;
  DroppedOrders dropped_;
  // matrices_[S - 1] holds M_S row-major: S rows of d+1 values.
  std::vector<std::vector<double>> matrices_;
};

}  // namespace radquad
