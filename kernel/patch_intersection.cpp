#include "kernel/patch_intersection.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <sstream>
#include <vector>

namespace radquad {
namespace {

using Corners = std::array<Eigen::Vector3d, 4>;

// The part of the line {point + t direction} inside the convex polygon `corners` (in its
// plane, which the line is assumed to lie in), as a parameter interval [t0, t1]; empty when
// t0 > t1. Each edge's inward half-plane cuts the interval.
void clipLineToPolygon(const Corners& corners, const Eigen::Vector3d& normal,
                       const Eigen::Vector3d& point, const Eigen::Vector3d& direction, double& t0,
                       double& t1) {
  for (int k = 0; k < 4; ++k) {
    const Eigen::Vector3d& p = corners[k];
    const Eigen::Vector3d edge = corners[(k + 1) % 4] - p;
    const Eigen::Vector3d inward = normal.cross(edge);  // counter-clockwise about the normal
    const double base = inward.dot(point - p);
    const double slope = inward.dot(direction);
    if (slope == 0.0) {
      if (base < 0.0) t0 = 1.0, t1 = 0.0;
      continue;
    }
    const double t = -base / slope;
    if (slope > 0.0) t0 = std::max(t0, t);
    else t1 = std::min(t1, t);
  }
}

// Area of the intersection of two convex quadrilaterals in one plane (Sutherland-Hodgman
// clipping of a by each edge of b, whose corners turn counter-clockwise about its own normal
// bNormal, then the shoelace formula).
double coplanarOverlapArea(const Corners& a, const Corners& b, const Eigen::Vector3d& bNormal) {
  std::vector<Eigen::Vector3d> polygon(a.begin(), a.end());
  for (int k = 0; k < 4 && !polygon.empty(); ++k) {
    const Eigen::Vector3d& p = b[k];
    const Eigen::Vector3d inward = bNormal.cross(b[(k + 1) % 4] - p);
    std::vector<Eigen::Vector3d> clipped;
    for (std::size_t i = 0; i < polygon.size(); ++i) {
      const Eigen::Vector3d& from = polygon[i];
      const Eigen::Vector3d& to = polygon[(i + 1) % polygon.size()];
      const double df = inward.dot(from - p), dt = inward.dot(to - p);
      if (df >= 0.0) clipped.push_back(from);
      if ((df >= 0.0) != (dt >= 0.0)) clipped.push_back(from + (df / (df - dt)) * (to - from));
    }
    polygon = std::move(clipped);
  }
  Eigen::Vector3d twiceArea = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < polygon.size(); ++i) {
    twiceArea += polygon[i].cross(polygon[(i + 1) % polygon.size()]);
  }
  return 0.5 * std::abs(twiceArea.dot(bNormal));
}

std::string format(double value) {
  std::ostringstream out;
  out.precision(6);
  out << value;
  return out.str();
}

}  // namespace

std::optional<std::string> patchesInterpenetrate(const Patch& a, const Patch& b) {
  const Corners ca = a.corners(), cb = b.corners();
  const double size = std::max({a.edgeU.norm(), a.edgeV.norm(), b.edgeU.norm(), b.edgeV.norm()});
  const double tolerance = 1e-9 * size;
  // Signed distances of each patch's corners to the other's plane.
  std::array<double, 4> da, db;
  for (int k = 0; k < 4; ++k) {
    da[k] = a.normal.dot(cb[k] - a.origin);  // b's corners against a's plane
    db[k] = b.normal.dot(ca[k] - b.origin);  // a's corners against b's plane
  }
  auto straddles = [&](const std::array<double, 4>& d) {
    const double lo = *std::min_element(d.begin(), d.end());
    const double hi = *std::max_element(d.begin(), d.end());
    return lo < -tolerance && hi > tolerance;
  };
  auto inPlane = [&](const std::array<double, 4>& d) {
    for (double x : d) {
      if (std::abs(x) > tolerance) return false;
    }
    return true;
  };
  if (inPlane(da) && inPlane(db)) {
    const double area = coplanarOverlapArea(ca, cb, b.normal);
    if (area > tolerance * size) {
      return "overlap in their common plane over an area of " + format(area);
    }
    return std::nullopt;
  }
  // Not coplanar: the interiors can share a segment only if each patch has corners strictly
  // on both sides of the other's plane; the shared segment lies on the planes' common line.
  if (!straddles(da) || !straddles(db)) return std::nullopt;
  const Eigen::Vector3d direction = a.normal.cross(b.normal);
  const double sine = direction.norm();
  if (sine < 1e-12) return std::nullopt;  // parallel planes that both straddle: impossible
  // A point on both planes: solve n_a.x = n_a.o_a, n_b.x = n_b.o_b on the line's normal plane.
  const double ha = a.normal.dot(a.origin), hb = b.normal.dot(b.origin);
  const Eigen::Vector3d point =
      (ha * b.normal.cross(direction) + hb * direction.cross(a.normal)) / (sine * sine);
  const Eigen::Vector3d unit = direction / sine;
  double t0 = -INFINITY, t1 = INFINITY;
  clipLineToPolygon(ca, a.normal, point, unit, t0, t1);
  clipLineToPolygon(cb, b.normal, point, unit, t0, t1);
  if (t1 - t0 > tolerance) {
    return "cross each other along a segment of length " + format(t1 - t0);
  }
  return std::nullopt;
}

namespace {

double pointToSegment(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  const Eigen::Vector3d ab = b - a;
  const double t = std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
  return (a + t * ab - p).norm();
}

// Closest distance between segments [p0, p1] and [q0, q1] (Ericson, "Real-Time Collision
// Detection", 5.1.9), with the parallel case falling back to endpoint distances.
double segmentToSegment(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1,
                        const Eigen::Vector3d& q0, const Eigen::Vector3d& q1) {
  const Eigen::Vector3d d1 = p1 - p0, d2 = q1 - q0, r = p0 - q0;
  const double a = d1.squaredNorm(), e = d2.squaredNorm(), f = d2.dot(r), c = d1.dot(r);
  const double b = d1.dot(d2), denominator = a * e - b * b;
  double best = std::min({pointToSegment(p0, q0, q1), pointToSegment(p1, q0, q1),
                          pointToSegment(q0, p0, p1), pointToSegment(q1, p0, p1)});
  if (denominator > 1e-12 * a * e) {
    const double s = (b * f - c * e) / denominator, t = (a * f - b * c) / denominator;
    if (s > 0.0 && s < 1.0 && t > 0.0 && t < 1.0) {
      best = std::min(best, (p0 + s * d1 - (q0 + t * d2)).norm());
    }
  }
  return best;
}

double pointToPatch(const Eigen::Vector3d& point, const Patch& patch) {
  const Eigen::Vector2d uv = patch.parametersOf(point);
  if (uv.x() >= 0.0 && uv.x() <= 1.0 && uv.y() >= 0.0 && uv.y() <= 1.0) {
    return std::abs(patch.normal.dot(point - patch.origin));
  }
  const Corners c = patch.corners();
  double best = INFINITY;
  for (int k = 0; k < 4; ++k) best = std::min(best, pointToSegment(point, c[k], c[(k + 1) % 4]));
  return best;
}

}  // namespace

bool straddlesPlane(const Patch& plane, const Patch& element) {
  const double margin = 1e-9 * std::sqrt(std::max(plane.area, element.area));
  bool front = false, back = false;
  for (const Eigen::Vector3d& point : element.corners()) {
    const double height = plane.normal.dot(point - plane.origin);
    front = front || height > margin;
    back = back || height < -margin;
  }
  return front && back;
}

bool cutByTangentPlane(const Patch& receiver, const Patch& source) {
  return straddlesPlane(receiver, source) || straddlesPlane(source, receiver);
}

double patchDistance(const Patch& a, const Patch& b) {
  if (patchesInterpenetrate(a, b)) return 0.0;
  const Corners ca = a.corners(), cb = b.corners();
  double best = INFINITY;
  for (int k = 0; k < 4; ++k) {
    best = std::min({best, pointToPatch(ca[k], b), pointToPatch(cb[k], a)});
    for (int j = 0; j < 4; ++j) {
      best = std::min(best, segmentToSegment(ca[k], ca[(k + 1) % 4], cb[j], cb[(j + 1) % 4]));
    }
  }
  return best;
}

double segmentToPatchDistance(const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                              const Patch& patch) {
  const double ha = patch.normal.dot(a - patch.origin), hb = patch.normal.dot(b - patch.origin);
  if ((ha < 0.0) != (hb < 0.0)) {
    const Eigen::Vector2d uv = patch.parametersOf(a + (ha / (ha - hb)) * (b - a));
    if (uv.x() >= 0.0 && uv.x() <= 1.0 && uv.y() >= 0.0 && uv.y() <= 1.0) return 0.0;
  }
  const Corners c = patch.corners();
  double best = std::min(pointToPatch(a, patch), pointToPatch(b, patch));
  for (int k = 0; k < 4; ++k) best = std::min(best, segmentToSegment(a, b, c[k], c[(k + 1) % 4]));
  return best;
}

double nearnessRatio(const Patch& a, const Patch& b) {
  const Patch& smaller = a.area <= b.area ? a : b;
  return patchDistance(a, b) / std::min(smaller.edgeU.norm(), smaller.edgeV.norm());
}

bool polygonCrossesPatch(const std::vector<Eigen::Vector3d>& polygon, const Patch& patch) {
  const double size = std::max(patch.edgeU.norm(), patch.edgeV.norm());
  const double tolerance = 1e-9 * size;
  std::vector<double> heights;
  double lowest = 0.0, highest = 0.0;
  for (const auto& p : polygon) {
    heights.push_back(patch.normal.dot(p - patch.origin));
    lowest = std::min(lowest, heights.back());
    highest = std::max(highest, heights.back());
  }
  if (!(lowest < -tolerance && highest > tolerance)) return false;
  // The convex polygon meets the plane in a segment: its two edge crossings.
  std::vector<Eigen::Vector2d> ends;
  for (std::size_t i = 0, n = polygon.size(); i < n && ends.size() < 2; ++i) {
    const double a = heights[i], b = heights[(i + 1) % n];
    if ((a < 0.0) != (b < 0.0)) {
      const Eigen::Vector3d point = polygon[i] + (a / (a - b)) * (polygon[(i + 1) % n] - polygon[i]);
      ends.push_back(patch.parametersOf(point));
    }
  }
  if (ends.size() < 2) return false;
  // Liang-Barsky: the part of the segment inside [0,1]^2, shrunk by the tolerance.
  const double margin = tolerance / size;
  double t0 = 0.0, t1 = 1.0;
  const Eigen::Vector2d d = ends[1] - ends[0];
  for (int axis = 0; axis < 2; ++axis) {
    for (const double bound : {margin, 1.0 - margin}) {
      const bool lower = bound == margin;
      const double p = lower ? -d[axis] : d[axis];
      const double q = lower ? ends[0][axis] - bound : bound - ends[0][axis];
      if (p == 0.0) {
        if (q < 0.0) return false;
      } else {
        const double t = q / p;
        if (p < 0.0) t0 = std::max(t0, t);
        else t1 = std::min(t1, t);
      }
    }
  }
  return t1 - t0 > 0.0 && (t1 - t0) * (d.norm() * size) > tolerance;
}

}  // namespace radquad
