#include "radiosity/two_scale.h"

#include "kernel/legendre_basis.h"
#include "quadrature/gauss_legendre.h"

namespace radquad {

TwoScale::TwoScale(int degree) : degree_(degree) {
  validateBasisDegree(degree);
  const int n = degree + 1;
  // t^(h)[i'][i]: the integrand phi_i((h+x)/2) phi_i'(x) has degree <= 2d, so n = d+1 Gauss
  // points integrate it exactly.
  const GaussLegendreRule& gauss = gaussLegendreUnit(n);
  std::array<Eigen::MatrixXd, 2> half;
  std::vector<double> parentValues(static_cast<std::size_t>(n)),
      childValues(static_cast<std::size_t>(n));
  for (int h = 0; h < 2; ++h) {
    half[std::size_t(h)].setZero(n, n);
    for (std::size_t k = 0; k < gauss.nodes.size(); ++k) {
      const double x = gauss.nodes[k];
      shiftedLegendreValues(degree, 0.5 * (h + x), parentValues.data());
      shiftedLegendreValues(degree, x, childValues.data());
      for (int ic = 0; ic < n; ++ic) {
        for (int ip = 0; ip < n; ++ip) {
          half[std::size_t(h)](ic, ip) +=
              gauss.weights[k] * parentValues[std::size_t(ip)] * childValues[std::size_t(ic)];
        }
      }
    }
  }
  const int functions = n * n;
  for (int c = 0; c < 4; ++c) {
    const Eigen::MatrixXd& tu = half[std::size_t(c / 2)];
    const Eigen::MatrixXd& tv = half[std::size_t(c % 2)];
    Eigen::MatrixXd& t = children_[std::size_t(c)];
    t.resize(functions, functions);
    for (int ic = 0; ic < n; ++ic)
      for (int jc = 0; jc < n; ++jc)
        for (int ip = 0; ip < n; ++ip)
          for (int jp = 0; jp < n; ++jp)
            t(ic * n + jc, ip * n + jp) = 0.5 * tu(ic, ip) * tv(jc, jp);
  }
}

}  // namespace radquad
