// Closed-form form factors between rectangles (J. R. Howell, "A Catalog of Radiation Heat
// Transfer Configuration Factors", cases C-11 and C-14), the independent anchors of the
// kernel tests.
#pragma once

#include <cmath>
#include <numbers>

namespace radquad::testing {

// Two directly opposed parallel rectangles a x b at distance c (Howell C-11).
inline double parallelRectanglesFormFactor(double a, double b, double c) {
  const double x = a / c, y = b / c;
  const double x2 = x * x, y2 = y * y;
  const double sum = std::log(std::sqrt((1 + x2) * (1 + y2) / (1 + x2 + y2))) +
                     x * std::sqrt(1 + y2) * std::atan(x / std::sqrt(1 + y2)) +
                     y * std::sqrt(1 + x2) * std::atan(y / std::sqrt(1 + x2)) - x * std::atan(x) -
                     y * std::atan(y);
  return 2.0 / (std::numbers::pi * x * y) * sum;
}

// From a rectangle of width w to a perpendicular rectangle of height h sharing an edge of
// length l with it (Howell C-14).
inline double perpendicularRectanglesFormFactor(double l, double w, double h) {
  const double W = w / l, H = h / l;
  const double W2 = W * W, H2 = H * H, R = std::sqrt(W2 + H2);
  const double logTerm = std::log((1 + W2) * (1 + H2) / (1 + W2 + H2)) +
                         W2 * std::log(W2 * (1 + W2 + H2) / ((1 + W2) * (W2 + H2))) +
                         H2 * std::log(H2 * (1 + H2 + W2) / ((1 + H2) * (H2 + W2)));
  return (W * std::atan(1 / W) + H * std::atan(1 / H) - R * std::atan(1 / R) + 0.25 * logTerm) /
         (std::numbers::pi * W);
}

}  // namespace radquad::testing
