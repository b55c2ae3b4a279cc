// The exact gold's inner integral (reference/source_moments.h): the radial moments J_m, one
// at a time and on eight lanes, against composite Gauss in long double; the loose edge rule
// against the tight one; the polar method against Lambert's formula.
#include <gtest/gtest.h>

#include <Eigen/Core>

#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <vector>

#include "kernel/input_error.h"
#include "quadrature/gauss_legendre.h"
#include "reference/exact_visibility.h"
#include "reference/source_moments.h"

namespace radquad {
namespace {

// J_m(R, H) = int_0^R rho^m / (rho^2 + H^2)^2 by 20-point Gauss on `pieces` pieces graded
// towards 0 (where the integrand varies on the scale H) as (p / pieces)^grading, in long double.
long double gradedRadialMoment(double R, double H, int m, int pieces, double grading) {
  const GaussLegendreRule& rule = gaussLegendreUnit(20);
  long double sum = 0.0L;
  for (int p = 0; p < pieces; ++p) {
    const double a = R * std::pow(double(p) / pieces, grading);
    const double b = R * std::pow(double(p + 1) / pieces, grading);
    for (int k = 0; k < 20; ++k) {
      const long double rho = a + (b - a) * rule.nodes[k];
      const long double d = rho * rho + (long double)H * H;
      sum += (b - a) * rule.weights[k] * std::pow(rho, m) / (d * d);
    }
  }
  return sum;
}

TEST(RadialMoments, MatchCompositeGaussIntegrationAtEveryScale) {
  // Against 200 pieces of 20-point Gauss.
  for (const double H : {1e-3, 0.3, 1.0, 7.0}) {
    for (const double R : {1e-3, 0.05, 0.9, 2.5, 40.0}) {
      double J[19];
      radialMoments(R, H, 18, J);
      for (int m = 0; m <= 18; ++m) {
        const long double expected = gradedRadialMoment(R, H, m, 200, 3.0);
        EXPECT_NEAR(J[m], double(expected), 1e-12 * std::fabs(double(expected)))
            << "m " << m << " R " << R << " H " << H;
      }
    }
  }
}

TEST(RadialMoments, LowPowersMatchCompositeGaussIntegrationAcrossEveryRule) {
  // Powers up to 8 (degree <= 3) take 8 or 12 Gauss points or the recurrences by R / H:
  // every branch and both sides of each switch (0.15, 0.85), against 400 pieces of
  // 20-point Gauss in long double, graded towards 0.
  for (const int maxPower : {4, 6, 8}) {
    for (const double X : {1e-4, 0.01, 0.1, 0.15, 0.1501, 0.3, 0.45, 0.4501, 0.6, 0.85, 0.8501,
                           0.87, 1.0, 1.3, 1.9, 2.0, 2.01, 3.0, 30.0}) {
      const double H = 0.7, R = X * H;
      double J[9];
      radialMoments(R, H, maxPower, J);
      for (int m = 0; m <= maxPower; ++m) {
        const long double expected = gradedRadialMoment(R, H, m, 400, 2.0);
        EXPECT_NEAR(J[m], double(expected), 5e-14 * std::fabs(double(expected)))
            << "m " << m << " of " << maxPower << ", R / H " << X;
      }
    }
  }
}

// Every lane of laneRadialMoments (the loose form or not) on each batch, at the powers 2, 4, 6
// and 8, against 400 pieces of 20-point Gauss in long double, within bound(maxPower) relative.
template <class Bound>
void expectLanesMatchQuadrature(const std::vector<std::array<double, 8>>& batches, bool loose,
                                const Bound& bound) {
  for (const int maxPower : {2, 4, 6, 8}) {
    for (const auto& X : batches) {
      double out[9 * 8];
      laneRadialMoments(X.data(), maxPower, out, loose);
      for (int k = 0; k < 8; ++k) {
        for (int m = 0; m <= maxPower; ++m) {
          const long double expected = gradedRadialMoment(X[std::size_t(k)], 1.0, m, 400, 2.0);
          EXPECT_NEAR(out[m * 8 + k], double(expected),
                      bound(maxPower) * std::fabs(double(expected)))
              << "m " << m << " of " << maxPower << ", X " << X[std::size_t(k)];
        }
      }
    }
  }
}

TEST(RadialMoments, EightLanesMatchCompositeGaussIntegrationWhateverTheirNeighbours) {
  // The inner integral's eight-lane form (degrees 0-3): the 12-point rule up to 0.85, the
  // recurrences (glibc's vector atan and log1p where built with them) above. Batches all on
  // one side of the switch, and batches that straddle it (each lane must keep its own
  // branch), against 400 pieces of 20-point Gauss in long double. The bound allows glibc's
  // documented 4 units in the last place of the vector atan and log1p, which the recurrences
  // amplify about 3.5 times at the switch (j_8 at R / H = 0.85 is 0.01): 2e-13 relative.
  const std::vector<std::array<double, 8>> batches = {
      {1e-4, 0.01, 0.1, 0.15, 0.3, 0.5, 0.7, 0.85},
      {0.8501, 0.87, 1.0, 1.3, 2.0, 3.0, 30.0, 300.0},
      {0.84, 0.86, 1e-3, 5.0, 0.85, 0.8500001, 0.31, 0.35},
  };
  expectLanesMatchQuadrature(batches, false, [](int) { return 2e-13; });
  double out[9 * 8];
  const double X[8] = {1, 1, 1, 1, 1, 1, 1, 1};
  EXPECT_THROW(laneRadialMoments(X, 5, out), InputError);
}

TEST(RadialMoments, LooseLanesStayWithinTheirBoundWhateverTheirNeighbours) {
  // The loose eight-lane form (accuracy 1e-6 or more): the 8-point rule up to 0.15, the
  // recurrences above, which lose digits as R / H falls. Against the same long-double
  // quadrature: 3e-10 relative up to the power 6 and 3e-8 at the power 8 (just above 0.15
  // the recurrences err by 1.3e-10 and 1.2e-8 with glibc's vector atan and log1p, 5e-11 and
  // 5e-9 with the scalar ones), on batches below, above and straddling the switch.
  const std::vector<std::array<double, 8>> batches = {
      {1e-4, 0.01, 0.05, 0.1, 0.12, 0.149, 0.15, 0.15},
      {0.1500001, 0.16, 0.2, 0.3, 0.5, 0.85, 3.0, 300.0},
      {0.14, 0.16, 1e-3, 5.0, 0.15, 0.1500001, 0.31, 0.85},
  };
  expectLanesMatchQuadrature(batches, true,
                             [](int maxPower) { return maxPower == 8 ? 3e-8 : 3e-10; });
}

TEST(SourceMoments, LooseAccuracyStaysWithinItsBoundOfTheAccurateIntegrals) {
  // The 8-point edge rule (accuracy 1e-6: error at most 2e-7 of the largest moment) against
  // the 12-point one (about 1e-14), at degrees 1 and 2, from points near (a twentieth of the
  // source's size) and far, above the interior and beyond the edges, on rings with a hole.
  // Degree 3 keeps the 12 points at any accuracy: the same values.
  const Patch source = Patch::make({0, 1, 1}, {1, 0, 0.2}, {0.1, -1, 0}, "source");
  VisibleRings rings;
  rings.add({{0, 0}, {1, 0}, {1, 1}, {0, 1}}, 1.0);
  rings.add({{0.2, 0.3}, {0.7, 0.25}, {0.5, 0.8}}, -1.0);
  std::mt19937_64 random(5);
  std::uniform_real_distribution<double> uniform(-0.5, 1.5);
  const Eigen::Vector3d normal = Eigen::Vector3d(0.1, -0.2, 1).normalized();
  for (const int degree : {1, 2, 3}) {
    const SourceMoments accurate(source, degree, 1e-14), loose(source, degree, 1e-6);
    const bool same = degree == 3;
    const int n = accurate.functions();
    std::vector<double> a(static_cast<std::size_t>(n)), b(static_cast<std::size_t>(n));
    int compared = 0;
    for (int k = 0; k < 60; ++k) {
      const Eigen::Vector3d x(uniform(random), uniform(random),
                              0.002 + 0.6 * (uniform(random) + 0.5));
      // The whole source in front of x's tangent plane (the visible part is clipped so).
      bool front = source.normal.dot(x - source.origin) > 0.0;
      for (const Eigen::Vector3d& corner : source.corners()) front = front && normal.dot(corner - x) > 0.0;
      if (!front) continue;
      accurate.compute(x, normal, rings, a.data());
      loose.compute(x, normal, rings, b.data());
      double largest = 0.0, difference = 0.0;
      for (int j = 0; j < n; ++j) {
        largest = std::max(largest, std::fabs(a[std::size_t(j)]));
        difference = std::max(difference, std::fabs(a[std::size_t(j)] - b[std::size_t(j)]));
      }
      EXPECT_LE(difference, same ? 0.0 : 2e-7 * largest) << "degree " << degree << " point " << k;
      // The looser rules differ: the test compares two computations, not one twice.
      if (difference > 0.0) ++compared;
    }
    if (!same) {
      EXPECT_GT(compared, 0) << "degree " << degree;
    }
  }
}

TEST(SourceMoments, PolarMethodReproducesLambertsFormula) {
  // Degree 0 both ways (contour formula, polar integration), on the source and on rings with
  // a hole, from points near and far, above the interior and beyond the edges.
  const Patch source = Patch::make({0, 1, 1}, {1, 0, 0.2}, {0.1, -1, 0}, "source");
  const SourceMoments moments(source, 0);
  VisibleRings rings;
  rings.add({{0, 0}, {1, 0}, {1, 1}, {0, 1}}, 1.0);
  rings.add({{0.2, 0.3}, {0.7, 0.25}, {0.5, 0.8}}, -1.0);
  std::mt19937_64 random(3);
  std::uniform_real_distribution<double> uniform(-0.5, 1.5);
  const Eigen::Vector3d normal(0, 0, 1);
  for (int k = 0; k < 40; ++k) {
    const Eigen::Vector3d x(uniform(random), uniform(random), 0.001 + 0.3 * (uniform(random) + 0.5));
    if (source.normal.dot(x - source.origin) <= 0.0) continue;
    double polar = 0.0;
    moments.computePolar(x, normal, rings, &polar);
    const double lambert = moments.formFactor(x, normal, rings);
    EXPECT_NEAR(polar, lambert, 1e-12 * std::fabs(lambert) + 1e-15) << "point " << k;
  }
}

}  // namespace
}  // namespace radquad
