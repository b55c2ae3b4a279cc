// Exact two-scale relations of the orthonormal tensor Legendre basis (docs/design.md,
// "Conventions") between an element and its four quadtree children.
//
// Child c = 2*cu + cv covers u in [cu/2, (cu+1)/2], v in [cv/2, (cv+1)/2] of its parent,
// so A_child = A_parent / 4. A parent function restricted to a child is a polynomial of the
// same degree, hence exactly a combination of the child's functions:
//   M^P_a|_C = sum_c T_C[c][a] M^C_c,
//   T_C[(i',j')][(i,j)] = (sqrt(A_C)/sqrt(A_P)) t^(cu)[i'][i] t^(cv)[j'][j]
//                       = t^(cu)[i'][i] t^(cv)[j'][j] / 2,
//   t^(h)[i'][i] = int_0^1 phi_i((h + x)/2) phi_i'(x) dx  (exact with (d+1)-point Gauss).
// Push (parent polynomial onto a child): b_C = T_C b_P (exact).
// Pull (area-weighted projection of the children onto the parent): b_P = sum_C T_C^T b_C.
// Since the children's bases together span the parent's, sum_C T_C^T T_C = I: push then
// pull is the identity, and pull keeps int B dA = sum_C sqrt(A_C) b_C[0].
#pragma once

#include <Eigen/Core>
#include <array>

namespace radquad {

// Coefficients of one element, one column per colour channel: (d+1)^2 rows x 3.
using Coefficients = Eigen::Matrix<double, Eigen::Dynamic, 3>;

class TwoScale {
 public:
  explicit TwoScale(int degree);

  int degree() const { return degree_; }
  // T_C for child c in 0..3 ((d+1)^2 x (d+1)^2).
  const Eigen::MatrixXd& child(int c) const { return children_[std::size_t(c)]; }

  Coefficients push(const Coefficients& parent, int c) const {
    return children_[std::size_t(c)] * parent;
  }
  // Adds T_C^T b_C to `parent`.
  void pullAdd(const Coefficients& childCoefficients, int c, Coefficients& parent) const {
    parent.noalias() += children_[std::size_t(c)].transpose() * childCoefficients;
  }

 private:
  int degree_;
  std::array<Eigen::MatrixXd, 4> children_;
};

}  // namespace radquad
