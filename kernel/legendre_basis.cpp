#include "kernel/legendre_basis.h"

#include <array>
#include <cmath>
#include <string>

#include "kernel/input_error.h"

namespace radquad {

void validateBasisDegree(int degree) {
  if (degree < 0 || degree > kMaxBasisDegree) {
    throw InputError("basis degree " + std::to_string(degree) + " is out of range: expected 0.." +
                     std::to_string(kMaxBasisDegree));
  }
}

void shiftedLegendreValues(int order, double t, double* values) {
  // Bonnet's recurrence (k+1) P_{k+1}(x) = (2k+1) x P_k(x) - k P_{k-1}(x), x = 2t-1.
  const double x = 2.0 * t - 1.0;
  double previous = 1.0;
  double current = x;
  values[0] = 1.0;
  if (order >= 1) values[1] = std::sqrt(3.0) * x;
  for (int k = 1; k < order; ++k) {
    const double next = ((2.0 * k + 1.0) * x * current - k * previous) / (k + 1.0);
    previous = current;
    current = next;
    values[k + 1] = std::sqrt(2.0 * (k + 1) + 1.0) * next;
  }
}

void tensorBasisValues(int degree, double u, double v, double* values) {
  std::array<double, kMaxBasisDegree + 1> alongU;
  std::array<double, kMaxBasisDegree + 1> alongV;
  shiftedLegendreValues(degree, u, alongU.data());
  shiftedLegendreValues(degree, v, alongV.data());
  const int n = degree + 1;
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) values[i * n + j] = alongU[i] * alongV[j];
  }
}

double legendreAbsoluteIntegral(int order) {
  if (order < 0 || order > kMaxBasisDegree) validateBasisDegree(order);
  if (order == 0) return 1.0;
  // |phi_k| is a polynomial of degree k between consecutive roots of P_k; a Gauss rule
  // with enough points on each interval between roots is exact. The roots are found by
  // bisection on sign changes of a fine grid (P_k has k simple roots in (-1,1)).
  auto phi = [order](double t) {
    std::array<double, kMaxBasisDegree + 1> values{};
    shiftedLegendreValues(order, t, values.data());
    return values[order];
  };
  std::array<double, kMaxBasisDegree + 2> breaks{};
  int count = 0;
  breaks[count++] = 0.0;
  const int grid = 4096;
  for (int g = 0; g < grid; ++g) {
    double lo = double(g) / grid;
    double hi = double(g + 1) / grid;
    if ((phi(lo) < 0) == (phi(hi) < 0)) continue;
    for (int iteration = 0; iteration < 200; ++iteration) {
      const double mid = 0.5 * (lo + hi);
      if ((phi(lo) < 0) == (phi(mid) < 0))
        lo = mid;
      else
        hi = mid;
    }
    breaks[count++] = 0.5 * (lo + hi);
  }
  breaks[count++] = 1.0;
  // 5-point Gauss-Legendre on [-1,1] is exact to degree 9 >= kMaxBasisDegree.
  static const double nodes[5] = {0.0, -0.5384693101056831, 0.5384693101056831, -0.9061798459386640,
                                  0.9061798459386640};
  static const double weights[5] = {0.5688888888888889, 0.4786286704993665, 0.4786286704993665,
                                    0.2369268850561891, 0.2369268850561891};
  double total = 0.0;
  for (int interval = 0; interval + 1 < count; ++interval) {
    const double a = breaks[interval];
    const double b = breaks[interval + 1];
    for (int q = 0; q < 5; ++q) {
      total +=
          0.5 * (b - a) * weights[q] * std::fabs(phi(0.5 * (a + b) + 0.5 * (b - a) * nodes[q]));
    }
  }
  return total;
}

}  // namespace radquad
