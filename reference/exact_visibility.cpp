#include "reference/exact_visibility.h"

#include <polyclipping/clipper.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace radquad {
namespace {

// Clipper's integer grid on the source's unit square: 2^44 steps (a resolution of 6e-14).
constexpr double kClipperScale = 17592186044416.0;
// Points this close to the apex (relative to x's height over the source plane) are cut: a
// polygon through x itself casts a shadow of zero area.
constexpr double kApexMargin = 1e-12;

// planeSlack from the plane's |normal|_1 and |offset|.
double slackOf(double normalNorm, double offsetMagnitude, double reach) {
  return 64.0 * std::numeric_limits<double>::epsilon() * (normalNorm * reach + offsetMagnitude);
}

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

double planeSlack(const Eigen::Vector3d& normal, double offset, double reach) {
  return slackOf(normal.lpNorm<1>(), std::abs(offset), reach);
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

namespace {

// Whether every edge of the ring is at least `shortest` long (in its larger coordinate).
bool edgesAtLeast(const SourceRing& ring, double shortest) {
  for (std::size_t i = 0, n = ring.size(); i < n; ++i) {
    if (!((ring[(i + 1) % n] - ring[i]).cwiseAbs().maxCoeff() >= shortest)) return false;
  }
  return true;
}

// At most this many rings (intersections of overlapping shadows) by inclusion-exclusion;
// beyond, the union by Clipper.
constexpr std::size_t kMaxInclusionExclusionRings = 64;

}  // namespace

ExactVisibility::ExactVisibility(const Link& link, bool inclusionExclusion)
    : link_(link), inclusionExclusion_(inclusionExclusion) {
  const Patch& source = link.source;
  const double uu = source.edgeU.dot(source.edgeU), uv = source.edgeU.dot(source.edgeV),
               vv = source.edgeV.dot(source.edgeV);
  const double determinant = uu * vv - uv * uv;
  dualU_ = (vv * source.edgeU - uv * source.edgeV) / determinant;
  dualV_ = (uu * source.edgeV - uv * source.edgeU) / determinant;
  if (!link.hasOccluders()) return;
  std::vector<Eigen::Vector3d> corners;
  for (const auto& c : link.receiver.corners()) corners.push_back(c);
  for (const auto& c : link.source.corners()) corners.push_back(c);
  double scale = 0.0;
  for (const auto& c : corners) scale = std::max(scale, c.cwiseAbs().maxCoeff());
  const std::vector<Eigen::Vector4d> planes = convexHullPlanes(corners);
  const double tolerance = 1e-9 * scale;
  for (const auto& polygon : link.occluders->polygons()) {
    bool outside = false;
    for (const auto& plane : planes) {
      outside = true;
      for (const auto& p : polygon) {
        if (plane.head<3>().dot(p) + plane[3] <= tolerance) {
          outside = false;
          break;
        }
      }
      if (outside) break;
    }
    if (!outside) {
      candidates_.push_back(polygon);
      candidateReach_.push_back(polygonReach(polygon));
    }
  }
  statistics_.candidateOccluders = candidates_.size();
}

void ExactVisibility::visibleRings(const Eigen::Vector3d& x, VisibleRings& out) {
  out.clear();
  const Patch& source = link_.source;
  const Eigen::Vector3d& nr = link_.receiver.normal;
  const double height = source.normal.dot(x - source.origin);
  if (!(height > 0.0)) return;  // on or behind the one-sided source
  // S': the source clipped to the half-space in front of x's tangent plane.
  const auto corners = source.corners();
  clipA_.assign(corners.begin(), corners.end());
  clipConvexPolygon(clipA_, nr, -nr.dot(x),
                    planeSlack(nr, -nr.dot(x), std::max(polygonReach(clipA_), x.lpNorm<Eigen::Infinity>())),
                    clipB_);
  if (clipB_.size() < 3) return;
  std::swap(front_, clipB_);
  const std::vector<Eigen::Vector3d>& front = front_;
  SourceRing& visible = out.add(1.0);
  for (const auto& p : front) {
    visible.push_back({(p - source.origin).dot(dualU_), (p - source.origin).dot(dualV_)});
  }
  if (!(ringArea(visible) > 0.0)) {
    out.clear();
    return;
  }
  if (candidates_.empty()) return;

  // The pyramid with apex x over S', as half-spaces normal . p + offset >= 0.
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  for (const auto& p : front) centroid += p;
  centroid /= double(front.size());
  std::vector<Eigen::Vector4d>& pyramid = pyramid_;
  pyramid.clear();
  pyramid.push_back({source.normal.x(), source.normal.y(), source.normal.z(),
                     -source.normal.dot(source.origin)});
  const double apexCut = source.normal.dot(source.origin) + height * (1.0 - kApexMargin);
  pyramid.push_back({-source.normal.x(), -source.normal.y(), -source.normal.z(), apexCut});
  for (std::size_t i = 0; i < front.size(); ++i) {
    const Eigen::Vector3d& a = front[i];
    const Eigen::Vector3d& b = front[(i + 1) % front.size()];
    // A source corner on x's tangent plane up to rounding (receiver and source sharing an
    // edge or a corner, in a frame not aligned with the axes) leaves two copies of it an
    // ulp apart: the plane through x and that edge would point anywhere and cut shadows at
    // random. An edge that short bounds nothing (its neighbours' planes close the pyramid).
    if (!((b - a).norm() > 1e-9 * (a - x).norm())) continue;
    Eigen::Vector3d normal = (a - x).cross(b - x);
    if (normal.squaredNorm() == 0.0) continue;
    if (normal.dot(centroid - x) < 0.0) normal = -normal;
    pyramid.push_back({normal.x(), normal.y(), normal.z(), -normal.dot(x)});
  }

  // The shadows, in storage kept from point to point (shadows_[0, shadowCount)).
  std::size_t shadowCount = 0;
  shadowBounds_.clear();
  // The side of a pyramid plane that clipConvexPolygon keeps: a vertex within the plane's
  // rounding slack lies on it (an occluder lying on the source, in a frame not aligned with
  // the axes, has its vertices at +-1e-17 from the source's plane: it is kept whole).
  // Per plane, the parts of planeSlack that do not depend on the candidate.
  planeNorms_.clear();
  for (const auto& plane : pyramid) {
    planeNorms_.push_back({plane.head<3>().lpNorm<1>(), std::abs(plane[3])});
  }
  for (std::size_t c = 0; c < candidates_.size(); ++c) {
    const std::vector<Eigen::Vector3d>& polygon = candidates_[c];
    const double reach = candidateReach_[c];
    slack_.clear();
    for (const auto& [norm, offset] : planeNorms_) {
      slack_.push_back(slackOf(norm, offset, reach));
    }
    slack_[1] = 0.0;  // the cut below the apex keeps every projection's depth positive
    // One pass over the candidate's own vertices: a plane with every vertex outside rejects
    // it; the planes with a vertex outside are the only ones that cut. A plane with every
    // vertex of the candidate inside has every vertex of its clipped parts inside too (they
    // lie on segments between those vertices), so it is not tried again.
    bool rejected = false;
    cutting_.clear();
    for (std::size_t k = 0; k < pyramid.size() && !rejected; ++k) {
      std::size_t inside = 0;
      for (const auto& p : polygon) {
        inside += pyramid[k].head<3>().dot(p) + pyramid[k][3] >= -slack_[k];
      }
      rejected = inside == 0;
      if (inside < polygon.size()) cutting_.push_back(k);
    }
    if (rejected) continue;
    const std::vector<Eigen::Vector3d>* clipped = &polygon;
    for (std::size_t k : cutting_) {
      clipConvexPolygon(*clipped, pyramid[k].head<3>(), pyramid[k][3], slack_[k], clipB_);
      std::swap(clipA_, clipB_);
      clipped = &clipA_;
      if (clipA_.size() < 3) break;
    }
    if (clipped->size() < 3) continue;
    if (shadowCount == shadows_.size()) shadows_.emplace_back();
    SourceRing& shadow = shadows_[shadowCount];
    shadow.clear();
    Eigen::Vector4d bounds(1e300, 1e300, -1e300, -1e300);
    for (const auto& q : *clipped) {
      const double depth = height - source.normal.dot(q - source.origin);  // > 0 inside
      const Eigen::Vector3d y = x + (q - x) * (height / depth);
      const Eigen::Vector2d uv((y - source.origin).dot(dualU_), (y - source.origin).dot(dualV_));
      shadow.push_back(uv);
      bounds = {std::min(bounds[0], uv.x()), std::min(bounds[1], uv.y()),
                std::max(bounds[2], uv.x()), std::max(bounds[3], uv.y())};
    }
    const double area = ringArea(shadow);
    if (area == 0.0 || !std::isfinite(area)) continue;
    if (area < 0.0) std::reverse(shadow.begin(), shadow.end());
    ++shadowCount;
    shadowBounds_.push_back(bounds);
  }
  if (shadowCount == 0) return;

  // Shadows that overlap no other shadow count as they are; only those that overlap some
  // other go to Clipper's union (one call for all of them: the union of disjoint groups is
  // their rings side by side).
  std::vector<char>& overlaps = overlaps_;
  overlaps.assign(shadowCount, 0);
  for (std::size_t i = 0; i < shadowCount; ++i) {
    for (std::size_t j = i + 1; j < shadowCount; ++j) {
      if (overlaps[i] && overlaps[j]) continue;
      const auto& a = shadowBounds_[i];
      const auto& b = shadowBounds_[j];
      if (a[0] < b[2] && b[0] < a[2] && a[1] < b[3] && b[1] < a[3] &&
          convexRingsOverlap(shadows_[i], shadows_[j])) {
        overlaps[i] = overlaps[j] = 1;
      }
    }
  }
  std::size_t overlapping = 0;
  for (std::size_t i = 0; i < shadowCount; ++i) {
    if (overlaps[i]) {
      ++overlapping;
    } else {
      out.add(shadows_[i], -1.0);
    }
  }
  if (overlapping == 0) return;
  ++statistics_.unions;
  if (inclusionExclusion_ && subtractOverlapping(shadowCount, out)) return;
  // The paths keep their storage from point to point too (Clipper's own edges do not).
  ClipperLib::Paths& paths = clipperPaths_;
  paths.resize(overlapping);
  for (std::size_t i = 0, path = 0; i < shadowCount; ++i) {
    if (!overlaps[i]) continue;
    paths[path].clear();
    for (const auto& p : shadows_[i]) {
      paths[path].push_back({ClipperLib::cInt(std::llround(p.x() * kClipperScale)),
                             ClipperLib::cInt(std::llround(p.y() * kClipperScale))});
    }
    ++path;
  }
  ClipperLib::Clipper clipper;
  clipper.AddPaths(paths, ClipperLib::ptSubject, true);
  ClipperLib::Paths& united = clipperUnion_;
  clipper.Execute(ClipperLib::ctUnion, united, ClipperLib::pftNonZero, ClipperLib::pftNonZero);
  const std::size_t first = out.count();
  double total = 0.0;
  for (const auto& path : united) {
    if (path.size() < 3) continue;
    SourceRing& ring = out.add(-1.0);
    for (const auto& p : path) ring.push_back({double(p.X) / kClipperScale, double(p.Y) / kClipperScale});
    total += ringArea(ring);
  }
  // Outer rings of the union must count positive, holes negative, in this file's convention.
  if (total < 0.0) {
    for (std::size_t r = first; r < out.count(); ++r) out.setSign(r, 1.0);
  }
}

bool ExactVisibility::subtractOverlapping(std::size_t shadowCount, VisibleRings& out) {
  // The union of the overlapping shadows P_i by inclusion-exclusion: its integral is the sum
  // over every set S of them whose common part has area, of (-1)^(|S| + 1) times the
  // integral over that part, a convex ring (the intersection of convex rings). Subtracted
  // from S', the sets of odd size count -1, those of even size +1. The sets are those of a
  // depth-first search, each extended by later shadows only while its part overlaps them.
  // Rings with an edge shorter than 1e-8 of the shadows' extent (a vertex repeated where an
  // occluder's vertex lies on a pyramid plane) have no direction to cut by, and too many
  // sets cost more than the union: then Clipper forms the union instead (false).
  overlapping_.clear();
  Eigen::Vector2d low(1e300, 1e300), high(-1e300, -1e300);
  for (std::size_t i = 0; i < shadowCount; ++i) {
    if (!overlaps_[i]) continue;
    overlapping_.push_back(i);
    low = low.cwiseMin(shadowBounds_[i].head<2>());
    high = high.cwiseMax(shadowBounds_[i].tail<2>());
  }
  const double shortest = 1e-8 * (high - low).maxCoeff();
  for (std::size_t i : overlapping_) {
    if (!edgesAtLeast(shadows_[i], shortest)) return false;
  }
  const std::size_t first = out.count();
  const std::size_t n = overlapping_.size();
  if (intersections_.size() < n + 1) {
    intersections_.resize(n + 1);
    intersectionBounds_.resize(n + 1);
  }
  // One set per stack entry: (its last shadow's place in overlapping_, its depth); the
  // set's part is intersections_[depth + 1], with its bounding box (low u, low v, high u,
  // high v) in intersectionBounds_.
  std::vector<std::pair<std::size_t, std::size_t>>& stack = setStack_;
  stack.clear();
  for (std::size_t k = n; k-- > 0;) stack.push_back({k, 0});
  // Depth-first: a set's part is built from its parent's, which stays in intersections_ at
  // the depth below until every extension of the parent is done.
  while (!stack.empty()) {
    const auto [k, depth] = stack.back();
    stack.pop_back();
    const SourceRing& shadow = shadows_[overlapping_[k]];
    const Eigen::Vector4d& bounds = shadowBounds_[overlapping_[k]];
    SourceRing& part = intersections_[depth + 1];
    Eigen::Vector4d& partBounds = intersectionBounds_[depth + 1];
    if (depth == 0) {
      part = shadow;
      partBounds = bounds;
    } else {
      const Eigen::Vector4d& parentBounds = intersectionBounds_[depth];
      if (!(parentBounds[0] < bounds[2] && bounds[0] < parentBounds[2] &&
            parentBounds[1] < bounds[3] && bounds[1] < parentBounds[3])) {
        continue;
      }
      intersectConvexRings(intersections_[depth], shadow, part, scratchRing_);
      if (part.size() < 3 || !(ringArea(part) > 0.0)) continue;
      partBounds = {part.front().x(), part.front().y(), part.front().x(), part.front().y()};
      for (const auto& p : part) {
        partBounds = {std::min(partBounds[0], p.x()), std::min(partBounds[1], p.y()),
                      std::max(partBounds[2], p.x()), std::max(partBounds[3], p.y())};
      }
    }
    if (out.count() - first >= kMaxInclusionExclusionRings) {
      out.truncate(first);
      return false;
    }
    out.add(part, depth % 2 == 0 ? -1.0 : 1.0);
    // Its extensions by later shadows, the earliest on top.
    for (std::size_t later = n; later-- > k + 1;) stack.push_back({later, depth + 1});
  }
  return true;
}

}  // namespace radquad
