// phi_k(t) = sqrt(2k+1) P_k(2t-1) for any k by Bonnet's recurrence, written apart from the
// basis code (which stops at degree 8) so the quadrature tests have an independent probe.
#pragma once

#include <cmath>

namespace radquad::testing {

inline double legendreAt(int k, double t) {
  const double x = 2 * t - 1;
  if (k == 0) return 1.0;
  double previous = 1.0, current = x;
  for (int m = 1; m < k; ++m) {
    const double next = ((2.0 * m + 1) * x * current - m * previous) / (m + 1);
    previous = current;
    current = next;
  }
  return std::sqrt(2.0 * k + 1) * current;
}

}  // namespace radquad::testing
