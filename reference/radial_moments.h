// The radial moments of the exact gold's inner integral (source_moments.h) in their
// eight-lane form: the recurrence thresholds and the vectorised loops over a batch's lanes,
// shared by the batched polar integral (source_moments.cpp) and the exposed entries
// (radial_moments.cpp); and the lane batches themselves (kLanes, sumLanes), which Lambert's
// formula (visible_form_factor.cpp) fills too. Not part of the reference's interface. Include
// it only from files compiled with the vector-math flags of reference/CMakeLists.txt.
#pragma once

#include <cmath>
#include <cstddef>

#include "kernel/legendre_basis.h"
#include "quadrature/gauss_legendre.h"

// With -fopenmp-simd (GCC, reference/CMakeLists.txt) the loops over a node batch's lanes that
// call atan and log1p call glibc's vector versions (libmvec: 8 lanes with AVX-512, 4 with
// AVX2), which err by at most 4 units in the last place; elsewhere, the scalar functions.
// The declarations add the vector variants to glibc's own (global, C linkage) functions.
#if defined(RADQUAD_VECTOR_MATH)
extern "C" {
#pragma omp declare simd notinbranch
double atan(double) noexcept;
#pragma omp declare simd notinbranch
double log1p(double) noexcept;
}
#endif

namespace radquad::detail {

// A batch's lanes: the edge nodes of one receiver point (degree <= 3, source_moments.cpp) and
// the edges of its visible rings (visible_form_factor.cpp) go kLanes at a time through loops
// over the lanes with no branch, which the compiler turns into vector instructions.
inline constexpr int kLanes = 8;

// The highest radial power: 2d + 2 at the highest basis degree d.
inline constexpr int kMaxPower = 2 * kMaxBasisDegree + 2;

// Where R / H reaches this, the radial moments of degrees <= 3 (powers <= 8) are taken by
// the recurrences; below, by a Gauss rule (scaledRadialMoments, laneRadialMoments).
inline constexpr double kRecurrenceFrom = 0.85;
// At a loose accuracy (1e-6 or more) the eight-lane form takes the recurrences from 0.15,
// and the 8-point rule below (exact to 1.5e-14 there). The recurrences lose digits as R / H
// falls (each step subtracts terms about (R / H)^-2 times larger than its result): measured
// against Gauss rules in long double, just above 0.15 they err by at most 1.3e-10 relative
// up to the power 6 (degree 2) and 1.2e-8 at the power 8 (degree 3) with glibc's vector
// atan and log1p (5e-11 and 5e-9 with the scalar ones), against the 2e-7 that the 8-point
// edge rule allows.
inline constexpr double kLooseRecurrenceFrom = 0.15;

// j_m(X[k]) = int_0^X[k] r^m / (1 + r^2)^2 dr for m = 0..P on every lane: the N-point
// Gauss rule where X <= from and the recurrences above: from = 0.85 with N = 12 (as
// scaledRadialMoments, which takes 8 points below 0.15: 12 are as exact there), or
// kLooseRecurrenceFrom with N = 8; lanes on both sides of `from` compute both and keep each
// lane's own.
template <int P, int N>
void laneRadialMoments(const double* X, double from, double (&j)[P + 1][kLanes]) {
  static const GaussLegendreRule& rule = gaussLegendreUnit(N);
  bool small = false, large = false;
  for (int k = 0; k < kLanes; ++k) {
    small = small || X[k] <= from;
    large = large || !(X[k] <= from);  // NaN included: it then propagates
  }
  for (int m = 0; m <= P; ++m) {
    for (int k = 0; k < kLanes; ++k) j[m][k] = 0.0;
  }
  if (small) {
    for (int q = 0; q < N; ++q) {
      const double node = rule.nodes[std::size_t(q)], w = rule.weights[std::size_t(q)];
      double r[kLanes], term[kLanes];
      for (int k = 0; k < kLanes; ++k) {
        r[k] = X[k] * node;
        const double denominator = 1.0 + r[k] * r[k];
        term[k] = X[k] * w / (denominator * denominator);
      }
      for (int m = 0; m <= P; ++m) {
        for (int k = 0; k < kLanes; ++k) {
          j[m][k] += term[k];
          term[k] *= r[k];
        }
      }
    }
  }
  if (large) {
    double l[P + 1][kLanes], jr[P + 1][kLanes];
    double squares[kLanes];
    for (int k = 0; k < kLanes; ++k) squares[k] = X[k] * X[k];
#if defined(RADQUAD_VECTOR_MATH)
#pragma omp simd
#endif
    for (int k = 0; k < kLanes; ++k) l[0][k] = ::atan(X[k]);
#if defined(RADQUAD_VECTOR_MATH)
#pragma omp simd
#endif
    for (int k = 0; k < kLanes; ++k) l[1][k] = 0.5 * ::log1p(squares[k]);
    double power[kLanes];
    for (int k = 0; k < kLanes; ++k) power[k] = X[k];
    for (int m = 2; m <= P; ++m) {
      for (int k = 0; k < kLanes; ++k) {
        l[m][k] = power[k] * (1.0 / double(m - 1)) - l[m - 2][k];
        power[k] *= X[k];
      }
    }
    for (int k = 0; k < kLanes; ++k) {
      const double inverse = 1.0 / (1.0 + squares[k]);
      jr[0][k] = 0.5 * (X[k] * inverse + l[0][k]);
      jr[1][k] = 0.5 * squares[k] * inverse;
    }
    for (int m = 2; m <= P; ++m) {
      for (int k = 0; k < kLanes; ++k) jr[m][k] = l[m - 2][k] - jr[m - 2][k];
    }
    for (int m = 0; m <= P; ++m) {
      for (int k = 0; k < kLanes; ++k) j[m][k] = X[k] <= from ? j[m][k] : jr[m][k];
    }
  }
}

// The tight form (12 points up to 0.85) or the loose one (8 points up to 0.15).
template <int P>
void laneRadialMoments(const double* X, bool loose, double (&j)[P + 1][kLanes]) {
  if (loose) {
    laneRadialMoments<P, 8>(X, kLooseRecurrenceFrom, j);
  } else {
    laneRadialMoments<P, 12>(X, kRecurrenceFrom, j);
  }
}

// T[i] = the sum of the lanes of laneT[i] (i < entries), in a fixed order.
inline void sumLanes(const double* laneT, int entries, double* T) {
  for (int i = 0; i < entries; ++i) {
    const double* lanes = laneT + i * kLanes;
    T[i] = ((lanes[0] + lanes[1]) + (lanes[2] + lanes[3])) +
           ((lanes[4] + lanes[5]) + (lanes[6] + lanes[7]));
  }
}

}  // namespace radquad::detail
