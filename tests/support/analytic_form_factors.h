// Closed-form form factors that anchor the tests (Howell, "A Catalog of Radiation Heat
// Transfer Configuration Factors", configurations C-11, C-14 and B-3; Cohen and Wallace 1993,
// appendix), each an independent reason to believe a computed value.
#pragma once

#include <cmath>
#include <numbers>

namespace radquad::analytic {

// Two directly opposed parallel a x b rectangles at distance c (Howell C-11).
inline double parallelRectangles(double a, double b, double c) {
  const double x = a / c, y = b / c;
  const double x1 = std::sqrt(1 + x * x), y1 = std::sqrt(1 + y * y);
  return 2.0 / (std::numbers::pi * x * y) *
         (std::log(x1 * y1 / std::sqrt(1 + x * x + y * y)) + x * y1 * std::atan(x / y1) +
          y * x1 * std::atan(y / x1) - x * std::atan(x) - y * std::atan(y));
}

// From a w x l rectangle to an h x l rectangle sharing the edge of length l, at right angles
// (Howell C-14), with W = w/l, H = h/l.
inline double perpendicularRectangles(double w, double h, double l) {
  const double W = w / l, H = h / l;
  const double W2 = W * W, H2 = H * H, S = W2 + H2;
  const double logTerm = std::log((1 + W2) * (1 + H2) / (1 + S)) +
                         W2 * std::log(W2 * (1 + S) / ((1 + W2) * S)) +
                         H2 * std::log(H2 * (1 + S) / ((1 + H2) * S));
  return (W * std::atan(1 / W) + H * std::atan(1 / H) - std::sqrt(S) * std::atan(1 / std::sqrt(S)) +
          0.25 * logTerm) /
         (std::numbers::pi * W);
}

// From a differential area to a parallel a x b rectangle whose corner lies on its normal at
// distance c (Howell B-3).
inline double pointToCornerRectangle(double a, double b, double c) {
  const double A = a / c, B = b / c;
  const double a1 = std::sqrt(1 + A * A), b1 = std::sqrt(1 + B * B);
  return (A / a1 * std::atan(B / a1) + B / b1 * std::atan(A / b1)) / (2.0 * std::numbers::pi);
}

}  // namespace radquad::analytic
