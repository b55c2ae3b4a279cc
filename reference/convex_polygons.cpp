#include "reference/convex_polygons.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>

namespace radquad {
namespace {

// Sutherland-Hodgman for one half-space, in 2D or 3D: the vertices of `polygon` whose
// height(p) is >= 0 and the crossings of its edges where the height changes sign, in order,
// into `out`. A vertex of height exactly 0 is kept and ends no crossing.
template <class Point, class Height>
void clipToHalfSpace(const std::vector<Point>& polygon, const Height& heightOf,
                     std::vector<Point>& out) {
  out.clear();
  const std::size_t n = polygon.size();
  if (n == 0) return;
  double previousHeight = heightOf(polygon[n - 1]);
  for (std::size_t i = 0; i < n; ++i) {
    const Point& previous = polygon[(i + n - 1) % n];
    const Point& current = polygon[i];
    const double height = heightOf(current);
    if ((previousHeight > 0.0 && height < 0.0) || (previousHeight < 0.0 && height > 0.0)) {
      out.push_back(previous + (previousHeight / (previousHeight - height)) * (current - previous));
    }
    if (height >= 0.0) out.push_back(current);
    previousHeight = height;
  }
}

}  // namespace

double planeSlackOf(double normalNorm, double offsetMagnitude, double reach) {
  return 64.0 * std::numeric_limits<double>::epsilon() * (normalNorm * reach + offsetMagnitude);
}

double planeSlack(const Eigen::Vector3d& normal, double offset, double reach) {
  return planeSlackOf(normal.lpNorm<1>(), std::abs(offset), reach);
}

double polygonReach(const std::vector<Eigen::Vector3d>& polygon) {
  double reach = 0.0;
  for (const auto& p : polygon) reach = std::max(reach, p.lpNorm<Eigen::Infinity>());
  return reach;
}

void clipConvexPolygon(const std::vector<Eigen::Vector3d>& polygon, const Eigen::Vector3d& normal,
                       double offset, double slack, std::vector<Eigen::Vector3d>& out) {
  // A height within the slack is rounding: the vertex lies on the plane, is kept, and is
  // never the end of a crossing (so no vertex comes out twice).
  clipToHalfSpace(
      polygon,
      [&](const Eigen::Vector3d& p) {
        const double height = normal.dot(p) + offset;
        return std::abs(height) <= slack ? 0.0 : height;
      },
      out);
}

void clipConvexPolygon(const std::vector<Eigen::Vector3d>& polygon, const Eigen::Vector3d& normal,
                       double offset, std::vector<Eigen::Vector3d>& out) {
  clipConvexPolygon(polygon, normal, offset, planeSlack(normal, offset, polygonReach(polygon)), out);
}

std::vector<Eigen::Vector4d> convexHullPlanes(const std::vector<Eigen::Vector3d>& points) {
  double scale = 0.0;
  for (const auto& p : points) scale = std::max(scale, p.cwiseAbs().maxCoeff());
  const double tolerance = 1e-12 * std::max(scale, 1e-300);
  std::vector<Eigen::Vector4d> planes;
  const std::size_t n = points.size();
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = i + 1; j < n; ++j) {
      for (std::size_t k = j + 1; k < n; ++k) {
        Eigen::Vector3d normal = (points[j] - points[i]).cross(points[k] - points[i]);
        const double length = normal.norm();
        if (length <= 1e-12 * scale * scale) continue;
        normal /= length;
        double lowest = 0.0, highest = 0.0;
        for (const auto& p : points) {
          const double h = normal.dot(p - points[i]);
          lowest = std::min(lowest, h);
          highest = std::max(highest, h);
        }
        if (highest <= tolerance) {
          planes.push_back({normal.x(), normal.y(), normal.z(), -normal.dot(points[i])});
        } else if (lowest >= -tolerance) {
          planes.push_back({-normal.x(), -normal.y(), -normal.z(), normal.dot(points[i])});
        }
      }
    }
  }
  return planes;
}

bool convexRingsOverlap(const SourceRing& a, const SourceRing& b) {
  // Separating axis theorem: disjoint (or touching along a boundary) iff some edge of one
  // ring has the other entirely on its outer side.
  // An edge too short for its direction to be trusted is no axis: the clip leaves a repeated
  // vertex where an occluder's vertex lies exactly on a pyramid plane (every receiver point,
  // for a vertex on the source's plane), and a zero edge has every point "outside" it. The
  // cut is 1e-8 of the rings' extent: an edge's endpoints carry rounding of about 1e-16 of
  // that, so a kept edge's direction is off by at most 1e-8 and so is the width of any
  // overlap it could miss. Skipping an edge only sends a pair to the union that might have
  // been subtracted separately.
  if (a.empty() || b.empty()) return false;
  Eigen::Vector2d low = a.front(), high = a.front();
  for (const SourceRing* ring : {&a, &b}) {
    for (const auto& point : *ring) {
      low = low.cwiseMin(point);
      high = high.cwiseMax(point);
    }
  }
  const double shortest = 1e-8 * (high - low).maxCoeff();
  auto separated = [shortest](const SourceRing& p, const SourceRing& q) {
    for (std::size_t i = 0, n = p.size(); i < n; ++i) {
      const Eigen::Vector2d& from = p[i];
      const Eigen::Vector2d edge = p[(i + 1) % n] - from;
      if (!(edge.cwiseAbs().maxCoeff() > shortest)) continue;
      bool allOutside = true;
      for (const auto& point : q) {
        const Eigen::Vector2d offset = point - from;
        if (edge.x() * offset.y() - edge.y() * offset.x() > 0.0) {  // inside a ccw ring
          allOutside = false;
          break;
        }
      }
      if (allOutside) return true;
    }
    return false;
  };
  return !separated(a, b) && !separated(b, a);
}

double ringArea(const SourceRing& ring) {
  double twice = 0.0;
  for (std::size_t i = 0, n = ring.size(); i < n; ++i) {
    const Eigen::Vector2d& a = ring[i];
    const Eigen::Vector2d& b = ring[(i + 1) % n];
    twice += a.x() * b.y() - a.y() * b.x();
  }
  return 0.5 * twice;
}

void intersectConvexRings(const SourceRing& a, const SourceRing& b, SourceRing& out,
                          SourceRing& scratch) {
  out = a;
  for (std::size_t i = 0, n = b.size(); i < n && out.size() >= 3; ++i) {
    const Eigen::Vector2d& from = b[i];
    const Eigen::Vector2d edge = b[(i + 1) % n] - from;
    if (edge.x() == 0.0 && edge.y() == 0.0) continue;
    // Positive on the inner (left) side of the edge.
    clipToHalfSpace(
        out,
        [&](const Eigen::Vector2d& p) {
          return edge.x() * (p.y() - from.y()) - edge.y() * (p.x() - from.x());
        },
        scratch);
    std::swap(out, scratch);
  }
}

}  // namespace radquad
