// The radial moments J_m(R, H) = int_0^R rho^m / (rho^2 + H^2)^2 d rho of the exact gold's
// inner integral (source_moments.h): one at a time (radialMoments, degrees above 3) and the
// exposed eight-lane entry (laneRadialMoments; the lanes' loops are in radial_moments.h).
#include "reference/radial_moments.h"

#include <array>
#include <cmath>

#include "kernel/input_error.h"
#include "quadrature/gauss_legendre.h"
#include "reference/source_moments.h"

namespace radquad {
namespace {

using detail::kLanes;
using detail::kMaxPower;
using detail::kRecurrenceFrom;

constexpr int kRadialPoints = 16;

// j_m(X) = int_0^X r^m / (1 + r^2)^2 dr, m = 0..maxPower (N: the Gauss rule's points, a
// multiple of 4).
// Where X is small the recurrences (below) lose digits (l_m is a difference of terms about
// X^-2 times larger than itself, at every step), so a Gauss rule takes them. The integrand's
// only singularities are the poles at r = +-i: the smaller X, the larger their Bernstein
// ellipse about [0, X] and the fewer points reach rounding. For powers up to 8 (degree <= 3),
// measured against 30-digit quadrature on 400 values of X: 8 points up to X = 0.15, 12 up to
// 0.85 and the recurrences above 0.85 all err by at most 1.5e-14 relative. Higher powers lose
// more in the recurrences: 16 points up to X = 2 (below 1e-13).
template <int N>
void gaussRadialMoments(double X, int maxPower, double* out) {
  static const GaussLegendreRule& rule = gaussLegendreUnit(N);
  double r[N], term[N];
  for (int k = 0; k < N; ++k) {
    r[k] = X * rule.nodes[k];
    const double denominator = 1.0 + r[k] * r[k];
    term[k] = X * rule.weights[k] / (denominator * denominator);
  }
  for (int m = 0; m <= maxPower; ++m) {
    // Four partial sums: short dependency chains.
    double sum[4] = {0.0, 0.0, 0.0, 0.0};
    for (int k = 0; k < N; k += 4) {
      for (int j = 0; j < 4; ++j) sum[j] += term[k + j];
    }
    out[m] = (sum[0] + sum[1]) + (sum[2] + sum[3]);
    for (int k = 0; k < N; ++k) term[k] *= r[k];
  }
}

// Recurrences: l_m = int r^m / (1 + r^2) = X^(m-1) / (m-1) - l_(m-2), j_m = l_(m-2) - j_(m-2).
void recurrentRadialMoments(double X, int maxPower, double* out) {
  const double X2 = X * X;
  std::array<double, kMaxPower + 1> l{};
  l[0] = std::atan(X);
  if (maxPower >= 1) l[1] = 0.5 * std::log1p(X2);
  double power = X;  // X^(m-1)
  for (int m = 2; m <= maxPower; ++m) {
    l[m] = power / double(m - 1) - l[m - 2];
    power *= X;
  }
  out[0] = 0.5 * (X / (1.0 + X2) + l[0]);
  if (maxPower >= 1) out[1] = 0.5 * X2 / (1.0 + X2);
  for (int m = 2; m <= maxPower; ++m) out[m] = l[m - 2] - out[m - 2];
}

void scaledRadialMoments(double X, int maxPower, double* out) {
  if (maxPower <= 8) {
    if (X <= 0.15) return gaussRadialMoments<8>(X, maxPower, out);
    if (X <= kRecurrenceFrom) return gaussRadialMoments<12>(X, maxPower, out);
  } else if (X <= 2.0) {
    return gaussRadialMoments<kRadialPoints>(X, maxPower, out);
  }
  recurrentRadialMoments(X, maxPower, out);
}

}  // namespace

// J_m(R, H) = H^(m-3) j_m(R / H).
void radialMoments(double R, double H, int maxPower, double* out) {
  scaledRadialMoments(R / H, maxPower, out);
  double scale = 1.0 / (H * H * H);  // H^(m-3)
  for (int m = 0; m <= maxPower; ++m) {
    out[m] *= scale;
    scale *= H;
  }
}

void laneRadialMoments(const double* X, int maxPower, double* out, bool loose) {
  auto copy = [&](const auto& j) {
    for (int m = 0; m <= maxPower; ++m) {
      for (int k = 0; k < kLanes; ++k) out[m * kLanes + k] = j[m][k];
    }
  };
  switch (maxPower) {
    case 2: { double j[3][kLanes]; detail::laneRadialMoments<2>(X, loose, j); return copy(j); }
    case 4: { double j[5][kLanes]; detail::laneRadialMoments<4>(X, loose, j); return copy(j); }
    case 6: { double j[7][kLanes]; detail::laneRadialMoments<6>(X, loose, j); return copy(j); }
    case 8: { double j[9][kLanes]; detail::laneRadialMoments<8>(X, loose, j); return copy(j); }
    default: throw InputError("laneRadialMoments: maxPower must be 2, 4, 6 or 8");
  }
}

}  // namespace radquad
