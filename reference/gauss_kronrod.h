// Gauss-Kronrod pairs on [-1, 1] (Piessens, de Doncker-Kapenga, Ueberhuber and Kahaner,
// QUADPACK, 1983): the (3, 7) and (7, 15) pairs. The 2n + 1 Kronrod points j = 0..2n are in
// ascending order; the odd ones (j = 1, 3, ..., 2n - 1) carry the n-point Gauss rule. The
// Kronrod rule is exact for polynomials of degree 3n + 2 (11 and 23), the Gauss rule for
// degree 2n - 1 (5 and 13); their difference estimates the Gauss rule's error, a bound (far
// from tight on analytic integrands) on the Kronrod rule's.
#pragma once

#include <algorithm>

namespace radquad {

namespace gauss_kronrod_detail {
// Indexed by the distance from the end, i = min(j, 2n - j); i = n is the centre.
inline constexpr double kNodes15[8] = {
    0.991455371120812639206854697526329, 0.949107912342758524526189684047851,
    0.864864423359769072789712788640926, 0.741531185599394439863864773280788,
    0.586087235467691130294144845693013, 0.405845151377397166906606412076961,
    0.207784955007898467600689403773245, 0.000000000000000000000000000000000};
inline constexpr double kKronrodWeights15[8] = {
    0.022935322010529224963732008058970, 0.063092092629978553290700663189204,
    0.104790010322250183839876322541518, 0.140653259715525918745189590510238,
    0.169004726639267902826583426598550, 0.190350578064785409913256402421014,
    0.204432940075298892414161999234649, 0.209482141084727828012999174891714};
inline constexpr double kGaussWeights7[4] = {
    0.129484966168869693270611432679082, 0.279705391489276667901467771423780,
    0.381830050505118944950369775488975, 0.417959183673469387755102040816327};
inline constexpr double kNodes7[4] = {0.960491268708020283423507092629080,
                                      0.774596669241483377035853079956480,
                                      0.434243749346802558002071502844628, 0.0};
inline constexpr double kKronrodWeights7[4] = {
    0.104656226026467265193823857192073, 0.268488089868333440728569280666710,
    0.401397414775962222905051818618432, 0.450916538658474142345110087045571};
inline constexpr double kGaussWeights3[2] = {0.555555555555555555555555555555556,
                                             0.888888888888888888888888888888889};
}  // namespace gauss_kronrod_detail

class GaussKronrodPair {
 public:
  // The (3, 7) and (7, 15) pairs.
  static const GaussKronrodPair& sevenPoint() {
    static const GaussKronrodPair pair(3, gauss_kronrod_detail::kNodes7,
                                       gauss_kronrod_detail::kKronrodWeights7,
                                       gauss_kronrod_detail::kGaussWeights3);
    return pair;
  }
  static const GaussKronrodPair& fifteenPoint() {
    static const GaussKronrodPair pair(7, gauss_kronrod_detail::kNodes15,
                                       gauss_kronrod_detail::kKronrodWeights15,
                                       gauss_kronrod_detail::kGaussWeights7);
    return pair;
  }

  int points() const { return 2 * n_ + 1; }
  int gaussPoints() const { return n_; }
  // Point j (0 .. points() - 1) on [-1, 1], its Kronrod weight, and its Gauss weight (0 off
  // the Gauss nodes).
  double node(int j) const { return j < n_ ? -nodes_[index(j)] : nodes_[index(j)]; }
  double kronrodWeight(int j) const { return kronrod_[index(j)]; }
  double gaussWeight(int j) const {
    const int i = index(j);
    return (n_ - i) % 2 == 0 ? gauss_[(i - (n_ % 2)) / 2] : 0.0;
  }

 private:
  GaussKronrodPair(int n, const double* nodes, const double* kronrod, const double* gauss)
      : n_(n), nodes_(nodes), kronrod_(kronrod), gauss_(gauss) {}
  int index(int j) const { return std::min(j, 2 * n_ - j); }

  int n_;
  const double* nodes_;
  const double* kronrod_;
  const double* gauss_;
};

}  // namespace radquad
