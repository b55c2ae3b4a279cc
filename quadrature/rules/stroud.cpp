#include "quadrature/rules/stroud.h"

#include <array>
#include <cmath>
#include <memory>
#include <numbers>

namespace radquad {
namespace {

constexpr int kDimension = 4;
using Point = std::array<double, kDimension>;

// Cn 5-7 (Stroud 1971, p. 233; Stroud 1966, rule "c") on [-1,1]^n: the centre with weight
// 4/(5n+4), and the n 2^n points with one coordinate +-r and all others +-s, each with
// weight 5/((5n+4) 2^n), where
//   r^2 = (5n+4 + 2(n-1) sqrt(5n+4)) / (15n),  s^2 = (5n+4 - 2 sqrt(5n+4)) / (15n).
LinkSamples cn57Points() {
  const double n = kDimension;
  const double root = std::sqrt(5.0 * n + 4.0);
  const double r = std::sqrt((5.0 * n + 4.0 + 2.0 * (n - 1.0) * root) / (15.0 * n));
  const double s = std::sqrt((5.0 * n + 4.0 - 2.0 * root) / (15.0 * n));
  const double centreWeight = 4.0 / (5.0 * n + 4.0);
  const double outerWeight = 5.0 / ((5.0 * n + 4.0) * std::pow(2.0, n));
  LinkSamples points;
  auto toUnit = [](double x) { return 0.5 * (x + 1.0); };
  points.push(0.5, 0.5, 0.5, 0.5, centreWeight);
  for (int axis = 0; axis < kDimension; ++axis) {
    for (int signs = 0; signs < (1 << kDimension); ++signs) {
      Point x{};
      for (int i = 0; i < kDimension; ++i) {
        const double magnitude = i == axis ? r : s;
        x[i] = (signs >> i) & 1 ? -magnitude : magnitude;
      }
      points.push(toUnit(x[0]), toUnit(x[1]), toUnit(x[2]), toUnit(x[3]), outerWeight);
    }
  }
  return points;
}

// Cn 3-1 (Stroud 1971, p. 230; Stroud 1957) on [-1,1]^n: 2n points of equal weight; point
// k = 1..2n has, for r = 1..n/2, x_{2r-1} = sqrt(2/3) cos((2r-1) k pi / n) and
// x_{2r} = sqrt(2/3) sin((2r-1) k pi / n) (n = 4 is even: no odd last coordinate).
std::array<Point, 2 * kDimension> cn31Points() {
  std::array<Point, 2 * kDimension> points{};
  const double radius = std::sqrt(2.0 / 3.0);
  for (int k = 1; k <= 2 * kDimension; ++k) {
    for (int r = 1; r <= kDimension / 2; ++r) {
      const double angle = (2 * r - 1) * k * std::numbers::pi / kDimension;
      points[k - 1][2 * r - 2] = radius * std::cos(angle);
      points[k - 1][2 * r - 1] = radius * std::sin(angle);
    }
  }
  return points;
}

// Cn 3-1 on each receiver quadrant [s0, s0 + 1/2] x [t0, t0 + 1/2] x [0,1]^2 (Gershbein 1995,
// section 3: "degree 3 rule applied to 4 receiver quadrants").
LinkSamples hierarchicalCn31Points() {
  const auto base = cn31Points();
  const double weight = 1.0 / (4.0 * base.size());
  LinkSamples points;
  for (int quadrantS = 0; quadrantS < 2; ++quadrantS) {
    for (int quadrantT = 0; quadrantT < 2; ++quadrantT) {
      for (const Point& x : base) {
        points.push(0.5 * quadrantS + 0.25 * (x[0] + 1.0), 0.5 * quadrantT + 0.25 * (x[1] + 1.0),
                    0.5 * (x[2] + 1.0), 0.5 * (x[3] + 1.0), weight);
      }
    }
  }
  return points;
}

}  // namespace

StroudRule::StroudRule(std::string name, int degree, std::string citation, LinkSamples points)
    : name_(std::move(name)), degree_(degree), citation_(std::move(citation)) {
  samples_.isProduct = false;
  samples_.points = std::move(points);
}

std::shared_ptr<const Rule> StroudRule::cn57() {
  return std::shared_ptr<const Rule>(
      new StroudRule("Stroud65", 5,
                     "Stroud 1971, formula Cn 5-7 (Stroud 1966, Math. Comp. 20, rule c), n = 4; "
                     "Gershbein 1995, section 3",
                     cn57Points()));
}

std::shared_ptr<const Rule> StroudRule::hierarchicalCn31() {
  return std::shared_ptr<const Rule>(new StroudRule(
      "HierStroud", 3,
      "Stroud 1971, formula Cn 3-1 (Stroud 1957, MTAC 11), n = 4, on each of the 4 receiver "
      "quadrants; Gershbein 1995, section 3",
      hierarchicalCn31Points()));
}

}  // namespace radquad
