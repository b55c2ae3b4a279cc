// Form factor between two planar convex polygons in 3D without occlusion, computed from the
// contour-integral formulation rather than from an integral over the areas.
//
// Applying Stokes' theorem to both area integrals of the form factor kernel
// cos(theta1) cos(theta2) / (pi r^2) turns the fourfold area integral into a double line
// integral around the two boundaries (Sparrow, "A new and simpler formulation for radiative
// angle factors", J. Heat Transfer 85, 1963):
//
//   A1 F(1 -> 2) = 1/(2 pi) * sum_{i in edges(1)} sum_{j in edges(2)}
//                    integral_{edge i} integral_{edge j} ln|x - y| (dx . dy),
//
// where both boundaries run counter-clockwise about the front normal of their own polygon and
// the fronts face each other. Schroeder and Hanrahan ("On the form factor between two
// polygons", SIGGRAPH 1993) give the edge-pair integral in closed form (with dilogarithms of
// complex arguments for skew edges and separate limiting expressions for parallel edges and
// edges meeting at a vertex). Here the same edge-pair integral is evaluated semi-analytically:
//
//  * The inner integral over edge j, for a fixed point p, is elementary. Writing the edge as
//    y(t) = b + t d (unit d, 0 <= t <= L), with u the coordinate of p along the edge line and
//    h its distance from that line, one has |p - y(t)|^2 = (t - u)^2 + h^2 and
//
//      integral_0^L ln|p - y(t)| dt = [ s ln sqrt(s^2 + h^2) + (h atan(s/h) - s) ] from -u to L-u,
//
//    which stays finite (and continuous in p) when p lies on the edge or its line (h = 0). The
//    bracket h atan(s / h) - s is summed as a series where |s| << h, since its two terms then
//    nearly cancel.
//
//  * The outer integral over edge i is done numerically with a globally adaptive 21-point
//    Gauss-Kronrod rule, to a relative accuracy of 1e-14 or the rounding level of the
//    integrand, whichever is larger. The integrand is analytic except at the points of edge i
//    that lie closest to an endpoint of edge j or to the line of edge j; there it can have a
//    logarithmic singularity in its derivative (edges sharing a vertex, crossing, or overlapping
//    along a common line). The outer edge is split at all of these points beforehand, so every
//    such point sits at a subinterval end, where the adaptive bisection resolves it quickly.
//
// Only the dot product of the edge directions enters, so perpendicular edge pairs contribute
// nothing. Since the boundaries are closed, adding a constant to ln|x - y| leaves the sum
// unchanged; the kernel is taken as ln(|x - y| / r0), with r0 the distance between the polygon
// centroids, which keeps the individual terms small when the polygons are far apart and so
// limits cancellation in the sum. Even so the edge terms exceed their sum by about the ratio of
// the distance to the polygon size, so the relative accuracy degrades in proportion for
// polygons far apart compared with their size.
//
// Nothing here accounts for occlusion, and the formula presumes each polygon lies entirely in
// front of the other (the usual setting of the closed-form catalogue values).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <vector>

namespace radquad::analytic {

namespace polygon_form_factor_detail {

// A straight edge start + t * direction, 0 <= t <= length, with a unit direction.
struct Edge {
  Eigen::Vector3d start;
  Eigen::Vector3d direction;
  double length;
};

inline std::vector<Edge> edgesOf(const std::vector<Eigen::Vector3d>& polygon) {
  std::vector<Edge> edges;
  edges.reserve(polygon.size());
  for (std::size_t i = 0; i < polygon.size(); ++i) {
    const Eigen::Vector3d& a = polygon[i];
    const Eigen::Vector3d& b = polygon[(i + 1) % polygon.size()];
    const double length = (b - a).norm();
    if (length == 0.0) continue;  // repeated vertex: a zero-length edge contributes nothing
    edges.push_back({a, (b - a) / length, length});
  }
  return edges;
}

// Area of a planar polygon from its Newell normal.
inline double areaOf(const std::vector<Eigen::Vector3d>& polygon) {
  Eigen::Vector3d twiceAreaNormal = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < polygon.size(); ++i) {
    twiceAreaNormal += polygon[i].cross(polygon[(i + 1) % polygon.size()]);
  }
  return 0.5 * twiceAreaNormal.norm();
}

inline Eigen::Vector3d centroidOf(const std::vector<Eigen::Vector3d>& polygon) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& v : polygon) sum += v;
  return sum / static_cast<double>(polygon.size());
}

// A computed value with the sum of the magnitudes of the terms it was formed from; its rounding
// error is a few units in the last place of `magnitude`.
struct Sample {
  double value;
  double magnitude;
};

// h atan(s / h) - s, accurate also for |s| << h, where the two terms nearly cancel, and equal
// to -s for h = 0.
inline double hAtanMinusS(double s, double h) {
  if (std::abs(s) < 0.125 * h) {
    // h (atan x - x) = s * sum_{k >= 1} (-1)^k x^(2k) / (2k + 1) with x = s / h, |x| < 1/8.
    const double x2 = (s / h) * (s / h);
    double term = 1.0, sum = 0.0;
    for (int k = 1; k <= 10; ++k) {
      term *= -x2;
      sum += term / (2 * k + 1);
    }
    return s * sum;
  }
  return h * std::atan2(s, h) - s;
}

// integral_0^L ln(|p - (b + t d)| / r0) dt for the edge b + t d, in closed form.
inline Sample logPotentialOfEdge(const Eigen::Vector3d& p, const Edge& edge, double r0) {
  const Eigen::Vector3d w = p - edge.start;
  const double u = w.dot(edge.direction);            // coordinate of p along the edge line
  const double h = (w - u * edge.direction).norm();  // distance of p from the edge line
  const double s0 = -u, s1 = edge.length - u;
  // s ln(sqrt(s^2 + h^2) / r0), whose limit at s = h = 0 is zero.
  const auto sLog = [h, r0](double s) {
    return s == 0.0 ? 0.0 : s * std::log(std::hypot(s, h) / r0);
  };
  const double terms[4] = {sLog(s1), -sLog(s0), hAtanMinusS(s1, h), -hAtanMinusS(s0, h)};
  // The logarithms carry an absolute rounding error of a few ulps of one (the distances are
  // only known to relative precision), so |s| enters the magnitude besides the terms.
  const double magnitude = std::abs(terms[0]) + std::abs(terms[1]) + std::abs(terms[2]) +
                           std::abs(terms[3]) + std::abs(s0) + std::abs(s1);
  return {(terms[0] + terms[1]) + (terms[2] + terms[3]), magnitude};
}

// The 21-point Kronrod extension of the 10-point Gauss-Legendre rule on [-1, 1]: the nonnegative
// abscissae (odd indices are the Gauss points) and their weights.
// clang-format off
inline constexpr std::array<double, 11> kKronrodNodes = {
    0.995657163025808080735527280689003, 0.973906528517171720077964012084452,
    0.930157491355708226001207180059508, 0.865063366688984510732096688423493,
    0.780817726586416897063717578345042, 0.679409568299024406234327365114874,
    0.562757134668604683339000099272694, 0.433395394129247190799265943165784,
    0.294392862701460198131126603103866, 0.148874338981631210884826001129720,
    0.0};
inline constexpr std::array<double, 11> kKronrodWeights = {
    0.011694638867371874278064396062192, 0.032558162307964727478818972459390,
    0.054755896574351996031381300244580, 0.075039674810919952767043140916190,
    0.093125454583697605535065465083366, 0.109387158802297641899210590325805,
    0.123491976262065851077600525398739, 0.134709217311473325928054001771707,
    0.142775938577060080797094273138717, 0.147739104901338491374841515972068,
    0.149445554002916905664936468389821};
inline constexpr std::array<double, 5> kGaussWeights = {
    0.066671344308688137593568809893332, 0.149451349150580593145776339657697,
    0.219086362515982043995534934228163, 0.269266719309996355091226921569469,
    0.295524224714752870173892994651338};
// clang-format on

struct Interval {
  double a, b;
  double value;     // Kronrod estimate of the integral over [a, b]
  double error;     // |Kronrod - Gauss|
  double absValue;  // Kronrod estimate of the integral of |f|
  double noise;     // error estimate attainable in the presence of rounding in f
};

// The 21-point Gauss-Kronrod rule on [a, b] for an f returning a Sample.
template <class F>
Interval gaussKronrod21(const F& f, double a, double b) {
  const double center = 0.5 * (a + b), half = 0.5 * (b - a);
  const Sample fCenter = f(center);
  double kronrod = kKronrodWeights[10] * fCenter.value;
  double gauss = 0.0;
  double absKronrod = kKronrodWeights[10] * std::abs(fCenter.value);
  double magnitude = kKronrodWeights[10] * fCenter.magnitude;
  for (std::size_t i = 0; i < 10; ++i) {
    const double dx = half * kKronrodNodes[i];
    const Sample left = f(center - dx), right = f(center + dx);
    const double pair = left.value + right.value;
    kronrod += kKronrodWeights[i] * pair;
    absKronrod += kKronrodWeights[i] * (std::abs(left.value) + std::abs(right.value));
    magnitude += kKronrodWeights[i] * (left.magnitude + right.magnitude);
    if (i % 2 == 1) gauss += kGaussWeights[i / 2] * pair;
  }
  const double width = std::abs(half);
  constexpr double kNoiseUlps = 50.0 * std::numeric_limits<double>::epsilon();
  Interval interval;
  interval.a = a;
  interval.b = b;
  interval.value = kronrod * half;
  interval.error = std::abs(kronrod - gauss) * width;
  interval.absValue = absKronrod * width;
  interval.noise = kNoiseUlps * magnitude * width;
  return interval;
}

// Globally adaptive Gauss-Kronrod integration of f over the consecutive intervals between the
// sorted points `breaks`: the subinterval with the largest error estimate is bisected until the
// summed estimate falls below relTol times the integral of |f|, or to the rounding level of f.
template <class F>
double integrateAdaptive(const F& f, const std::vector<double>& breaks, double relTol) {
  constexpr int kMaxBisections = 2000;
  const auto byError = [](const Interval& x, const Interval& y) { return x.error < y.error; };
  std::vector<Interval> heap;
  for (std::size_t i = 0; i + 1 < breaks.size(); ++i) {
    heap.push_back(gaussKronrod21(f, breaks[i], breaks[i + 1]));
  }
  std::make_heap(heap.begin(), heap.end(), byError);
  const double minWidth = 1e-14 * (breaks.back() - breaks.front());
  for (int bisection = 0; bisection < kMaxBisections && !heap.empty(); ++bisection) {
    double error = 0.0, absValue = 0.0, noise = 0.0;
    for (const Interval& interval : heap) {
      error += interval.error;
      absValue += interval.absValue;
      noise += interval.noise;
    }
    if (error <= std::max(relTol * absValue, noise)) break;
    std::pop_heap(heap.begin(), heap.end(), byError);
    const Interval worst = heap.back();
    if (worst.b - worst.a < minWidth) break;  // cannot be resolved further in double precision
    heap.pop_back();
    const double middle = 0.5 * (worst.a + worst.b);
    heap.push_back(gaussKronrod21(f, worst.a, middle));
    std::push_heap(heap.begin(), heap.end(), byError);
    heap.push_back(gaussKronrod21(f, middle, worst.b));
    std::push_heap(heap.begin(), heap.end(), byError);
  }
  double total = 0.0;
  for (const Interval& interval : heap) total += interval.value;
  return total;
}

// integral over edge `outer` of integral over edge `inner` of ln(|x - y| / r0) ds dt, with s and
// t the arc lengths; the caller multiplies by the dot product of the edge directions.
inline double edgePairLogIntegral(const Edge& outer, const Edge& inner, double r0) {
  const double L = outer.length;
  // Points of the outer edge where the integrand may fail to be smooth: closest to either
  // endpoint of the inner edge, and closest to the inner edge's line.
  std::vector<double> breaks = {0.0, L};
  const Eigen::Vector3d innerEnd = inner.start + inner.length * inner.direction;
  breaks.push_back((inner.start - outer.start).dot(outer.direction));
  breaks.push_back((innerEnd - outer.start).dot(outer.direction));
  const double cosAngle = outer.direction.dot(inner.direction);
  const double sinSquared = 1.0 - cosAngle * cosAngle;
  if (sinSquared > 1e-12) {
    const Eigen::Vector3d w0 = outer.start - inner.start;
    breaks.push_back((cosAngle * inner.direction.dot(w0) - outer.direction.dot(w0)) / sinSquared);
  }
  const double merge = 1e-12 * L;
  for (double& s : breaks) s = std::clamp(s, 0.0, L);
  std::sort(breaks.begin(), breaks.end());
  std::vector<double> distinct = {0.0};
  for (double s : breaks) {
    if (s - distinct.back() > merge) distinct.push_back(s);
  }
  distinct.back() = L;  // the last point merged into L (or was L) stays exactly at the end

  const auto integrand = [&](double s) {
    return logPotentialOfEdge(outer.start + s * outer.direction, inner, r0);
  };
  return integrateAdaptive(integrand, distinct, 1e-14);
}

}  // namespace polygon_form_factor_detail

// Form factor F(from -> to) = (1 / A_from) * integral_from integral_to
// cos(theta_from) cos(theta_to) / (pi r^2) dA_to dA_from between two planar convex polygons,
// each given by its vertices counter-clockwise about its front normal, the fronts facing each
// other, without occlusion.
inline double polygonToPolygonFormFactor(const std::vector<Eigen::Vector3d>& from,
                                         const std::vector<Eigen::Vector3d>& to) {
  namespace detail = polygon_form_factor_detail;
  if (from.size() < 3 || to.size() < 3) {
    throw std::invalid_argument("polygonToPolygonFormFactor: a polygon needs three vertices");
  }
  const double areaFrom = detail::areaOf(from);
  if (!(areaFrom > 0.0)) {
    throw std::invalid_argument("polygonToPolygonFormFactor: degenerate source polygon");
  }
  const std::vector<detail::Edge> edgesFrom = detail::edgesOf(from);
  const std::vector<detail::Edge> edgesTo = detail::edgesOf(to);

  // Any positive r0 gives the same exact result; the centroid distance keeps terms small.
  double r0 = (detail::centroidOf(from) - detail::centroidOf(to)).norm();
  if (!(r0 > 0.0)) r0 = std::sqrt(areaFrom);

  double sum = 0.0;
  for (const detail::Edge& outer : edgesFrom) {
    for (const detail::Edge& inner : edgesTo) {
      const double cosAngle = outer.direction.dot(inner.direction);
      if (cosAngle == 0.0) continue;
      sum += cosAngle * detail::edgePairLogIntegral(outer, inner, r0);
    }
  }
  return sum / (2.0 * std::numbers::pi * areaFrom);
}

}  // namespace radquad::analytic
