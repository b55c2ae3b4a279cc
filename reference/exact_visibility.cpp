#include "reference/exact_visibility.h"

#include <polyclipping/clipper.hpp>

#include <algorithm>
#include <bit>
#include <cstdint>
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

ExactVisibility::ExactVisibility(const Link& link, ShadowUnion method)
    : link_(link), method_(method) {
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
  // Per plane, the edge of S' it stands on (-1: the source's plane and the cut below x).
  pyramidSide_.assign(2, -1);
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
    pyramidSide_.push_back(int(i));
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
    // The clipped polygon in 3D, in the ring's order, and its occluder: for the outline,
    // which asks which of its vertices lie on the planes of S''s edges (shadowSides).
    if (shadowCount == shadowPolygons_.size()) shadowPolygons_.emplace_back();
    std::vector<Eigen::Vector3d>& polygon3d = shadowPolygons_[shadowCount];
    polygon3d.assign(clipped->begin(), clipped->end());
    if (area < 0.0) {
      std::reverse(shadow.begin(), shadow.end());
      std::reverse(polygon3d.begin(), polygon3d.end());
    }
    if (shadowCount == shadowCandidate_.size()) shadowCandidate_.push_back(0);
    shadowCandidate_[shadowCount] = c;
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
  switch (method_) {
    case ShadowUnion::outline:
      if (subtractOutline(shadowCount, out)) return;
      return subtractClipperUnion(shadowCount, out);
    case ShadowUnion::inclusionExclusion:
      if (subtractOverlapping(shadowCount, out)) return;
      return subtractClipperUnion(shadowCount, out);
    case ShadowUnion::clipper: return subtractClipperUnion(shadowCount, out);
  }
}

void ExactVisibility::subtractClipperUnion(std::size_t shadowCount, VisibleRings& out) {
  ++statistics_.unionsByClipper;
  const std::vector<char>& overlaps = overlaps_;
  std::size_t overlapping = 0;
  for (std::size_t i = 0; i < shadowCount; ++i) overlapping += overlaps[i] != 0;
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

bool ExactVisibility::subtractOutline(std::size_t shadowCount, VisibleRings& out) {
  overlapping_.clear();
  if (shadowSides_.size() < shadowCount) shadowSides_.resize(shadowCount);
  for (std::size_t i = 0; i < shadowCount; ++i) {
    if (!overlaps_[i]) continue;
    overlapping_.push_back(i);
    // Per vertex, the planes of S''s edges it lies on, as the clip decides (within the
    // slacks it used for this occluder): bit s for edge s of S'.
    const double reach = candidateReach_[shadowCandidate_[i]];
    std::vector<std::uint32_t>& sides = shadowSides_[i];
    sides.clear();
    for (const auto& q : shadowPolygons_[i]) {
      std::uint32_t on = 0;
      for (std::size_t k = 2; k < pyramid_.size(); ++k) {
        const auto& [norm, offset] = planeNorms_[k];
        if (std::fabs(pyramid_[k].head<3>().dot(q) + pyramid_[k][3]) <=
            slackOf(norm, offset, reach)) {
          on |= std::uint32_t(1) << pyramidSide_[k];
        }
      }
      sides.push_back(on);
    }
  }
  return outline_.add(shadows_, overlapping_, shadowBounds_, shadowSides_, out.ring(0), -1.0, out);
}

bool UnionOutline::add(const std::vector<SourceRing>& rings,
                       const std::vector<std::size_t>& members,
                       const std::vector<Eigen::Vector4d>& bounds,
                       const std::vector<std::vector<std::uint32_t>>& onBorder,
                       const SourceRing& border, double sign, VisibleRings& out) {
  // The union's boundary is made of the pieces of the shadows' edges that lie outside every
  // other shadow; each keeps its shadow's (counter-clockwise) direction, so the pieces about
  // a hole of the union run clockwise about it. A piece of an edge of shadow i is covered by
  // shadow j where it lies on the inner side of every edge line of j (the shadows are
  // convex).
  //  - Where two edges cross, both pieces end at one point, computed once from the two
  //    lines in a fixed order: the outline closes up exactly, however small their angle.
  //  - Two edges along one line (the shorter's ends within 1e-13 of the coordinates' unit of
  //    the longer's line, the rounding of the projections; the pieces then differ by a
  //    sliver of that width): running opposite ways, the shadows lie on either side and the
  //    line is inside the union (touching occluders), so the line does not bound what the
  //    other covers; running the same way (two shadows cut by one pyramid plane), both lie on
  //    one side and the line is on the boundary once: the earlier shadow keeps it.
  //  - An edge shorter than 1e-12 of the shadows' extent (a vertex repeated where an
  //    occluder's vertex lies on a pyramid plane) cuts nothing as a line, its direction being
  //    rounding (its neighbours' lines bound the shadow there); as a piece it counts.
  Eigen::Vector2d low(1e300, 1e300), high(-1e300, -1e300);
  for (std::size_t i : members) {
    low = low.cwiseMin(bounds[i].head<2>());
    high = high.cwiseMax(bounds[i].tail<2>());
  }
  constexpr double kOnLine = 1e-13;
  const double shortest = 1e-12 * (high - low).maxCoeff();
  // Edge e of shadow i, as (i, e).
  using EdgeKey = std::pair<std::size_t, std::size_t>;
  const auto ends = [&](const EdgeKey& key) {
    const SourceRing& ring = rings[key.first];
    return std::pair<const Eigen::Vector2d&, const Eigen::Vector2d&>(
        ring[key.second], ring[(key.second + 1) % ring.size()]);
  };
  // Where the lines of two edges cross: the same bits whichever edge asks.
  const auto crossing = [&](EdgeKey first, EdgeKey second, const Eigen::Vector2d& fallback) {
    if (second < first) std::swap(first, second);
    const auto [a, b] = ends(first);
    const auto [c, d] = ends(second);
    const Eigen::Vector2d ab = b - a, cd = d - c, ac = c - a;
    const double denominator = ab.x() * cd.y() - ab.y() * cd.x();
    if (denominator == 0.0) return fallback;
    const double s = (ac.x() * cd.y() - ac.y() * cd.x()) / denominator;
    return Eigen::Vector2d(a + s * ab);
  };
  // Whether edges (p, q) and (a, b) lie along one line: the shorter's ends on the longer's
  // line (the longer's direction is the better known), the first key's on a tie.
  const auto alongOneLine = [&](const Eigen::Vector2d& p, const Eigen::Vector2d& q,
                                const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                                bool firstIsEarlier) {
    const Eigen::Vector2d pq = q - p, ab = b - a;
    const double lengthPQ = pq.norm(), lengthAB = ab.norm();
    const bool referencePQ = lengthPQ > lengthAB || (lengthPQ == lengthAB && firstIsEarlier);
    const Eigen::Vector2d& origin = referencePQ ? p : a;
    const Eigen::Vector2d& line = referencePQ ? pq : ab;
    const Eigen::Vector2d& u = referencePQ ? a : p;
    const Eigen::Vector2d& w = referencePQ ? b : q;
    const double onLine = kOnLine * std::max(lengthPQ, lengthAB);
    return std::fabs(line.x() * (u.y() - origin.y()) - line.y() * (u.x() - origin.x())) <= onLine &&
           std::fabs(line.x() * (w.y() - origin.y()) - line.y() * (w.x() - origin.x())) <= onLine;
  };
  // S' (`border`; every shadow lies inside it): a shadow edge along one of its edges
  // (both ends on the pyramid plane through x and that edge, as the 3D clip placed them)
  // bounds the union wherever it runs, and as a line it cuts nothing inside S'. Those edges
  // are not pieces: per edge of S', the parts of it they cover are merged and given as
  // segments from the first edge's start to the last one's end, vertices of the shadows
  // themselves, where the shadows' other edges begin and end: the outline closes up there to
  // the bit.
  const SourceRing& front = border;
  const std::size_t sides = front.size();
  // Per shadow and edge: (edge vector, squared length or 0 if too short to cut by, the edge of
  // S' it runs along or -1).
  if (edgeLines_.size() < rings.size()) edgeLines_.resize(rings.size());
  std::vector<BorderPart>& along = borderParts_;
  along.clear();
  for (std::size_t i : members) {
    const SourceRing& ring = rings[i];
    const std::vector<std::uint32_t>& on = onBorder[i];
    std::vector<Eigen::Vector4d>& lines = edgeLines_[i];
    lines.clear();
    for (std::size_t f = 0, m = ring.size(); f < m; ++f) {
      const Eigen::Vector2d& a = ring[f];
      const Eigen::Vector2d& b = ring[(f + 1) % m];
      const Eigen::Vector2d line = b - a;
      const bool cuts = line.cwiseAbs().maxCoeff() >= shortest;
      double borderSide = -1.0;
      const std::uint32_t common = on[f] & on[(f + 1) % m];
      if (common != 0 && cuts) {
        const std::size_t k = std::size_t(std::countr_zero(common));
        const Eigen::Vector2d& c = front[k];
        const Eigen::Vector2d side = front[(k + 1) % sides] - c;
        if (line.dot(side) > 0.0) {
          borderSide = double(k);
          const double squared = side.squaredNorm();
          along.push_back({k, (a - c).dot(side) / squared, (b - c).dot(side) / squared, a, b,
                            on[f], on[(f + 1) % m]});
        }
      }
      lines.push_back({line.x(), line.y(), cuts ? line.squaredNorm() : 0.0, borderSide});
    }
  }
  std::vector<CoveredPart>& covered = covered_;
  const std::size_t first = out.segmentCount();
  // The border: per edge of S', its covered parts in order along it, merged where they
  // overlap. Where the border turns a corner of S' (the last part on one side ends on the
  // next side's plane, and the first part there starts on this side's), the shadows' corners
  // may be different vertices an ulp apart: both parts end at S''s own corner.
  std::sort(along.begin(), along.end(), [](const BorderPart& x, const BorderPart& y) {
    return x.side < y.side || (x.side == y.side && x.from < y.from);
  });
  std::vector<BorderPart>& merged = mergedBorder_;
  merged.clear();
  for (std::size_t k = 0; k < along.size();) {
    BorderPart part = along[k];
    for (++k; k < along.size() && along[k].side == part.side && along[k].from <= part.to; ++k) {
      if (along[k].to > part.to) {
        part.to = along[k].to;
        part.end = along[k].end;
        part.endOn = along[k].endOn;
      }
    }
    merged.push_back(part);
  }
  for (std::size_t k = 0; k < merged.size(); ++k) {
    // The last part on its side, and the first part on the next side.
    BorderPart& part = merged[k];
    if (k + 1 < merged.size() && merged[k + 1].side == part.side) continue;
    const std::size_t nextSide = (part.side + 1) % sides;
    if (!(part.endOn >> nextSide & 1u)) continue;
    for (BorderPart& next : merged) {
      if (next.side != nextSide) continue;
      if (next.startOn >> part.side & 1u) {
        part.end = front[nextSide];
        next.start = front[nextSide];
      }
      break;  // the first on that side (in order)
    }
  }
  for (const BorderPart& part : merged) out.addSegment(part.start, part.end, sign);
  for (std::size_t i : members) {
    const SourceRing& shadow = rings[i];
    for (std::size_t e = 0, n = shadow.size(); e < n; ++e) {
      const Eigen::Vector2d& p = shadow[e];
      const Eigen::Vector2d& q = shadow[(e + 1) % n];
      const Eigen::Vector2d pq = q - p;
      if (!(pq.cwiseAbs().maxCoeff() > 0.0) || edgeLines_[i][e][3] >= 0.0) continue;
      const EdgeKey self{i, e};
      const double lengthSquared = pq.squaredNorm();
      const Eigen::Vector2d edgeLow = p.cwiseMin(q), edgeHigh = p.cwiseMax(q);
      covered.clear();
      for (std::size_t j : members) {
        if (j == i) continue;
        const Eigen::Vector4d& box = bounds[j];
        if (box[0] > edgeHigh.x() + kOnLine || edgeLow.x() > box[2] + kOnLine ||
            box[1] > edgeHigh.y() + kOnLine || edgeLow.y() > box[3] + kOnLine) {
          continue;
        }
        // The part [from, to] of the edge (p + t pq, t in [0, 1]) inside shadow j, and the
        // edges of j it enters and leaves by (none: the edge's own end).
        const SourceRing& cover = rings[j];
        const std::vector<Eigen::Vector4d>& lines = edgeLines_[j];
        CoveredPart part{0.0, 1.0, kNoEdge, kNoEdge};
        for (std::size_t f = 0, m = cover.size(); f < m && part.from < part.to; ++f) {
          if (lines[f].z() == 0.0 || lines[f][3] >= 0.0) continue;
          const Eigen::Vector2d& a = cover[f];
          const Eigen::Vector2d line = lines[f].head<2>();
          // Heights of p and q over the line, times its length: > 0 on the inner side.
          const double hp = line.x() * (p.y() - a.y()) - line.y() * (p.x() - a.x());
          const double hq = line.x() * (q.y() - a.y()) - line.y() * (q.x() - a.x());
          // hq - hp = line x pq: edges along one line have it within 2 kOnLine of the longer's
          // length (the test below), so the others skip it.
          const double turn = hq - hp;
          if (turn * turn <= 4.0 * kOnLine * kOnLine * std::max(lengthSquared, lines[f].z()) &&
              alongOneLine(p, q, a, cover[(f + 1) % m], self < EdgeKey{j, f})) {
            if (pq.dot(line) < 0.0 || j < i) continue;
            part.from = part.to;
            break;
          }
          if (hp >= 0.0 && hq >= 0.0) continue;
          if (hp <= 0.0 && hq <= 0.0) {
            part.from = part.to;
            break;
          }
          const double t = hp / (hp - hq);
          if (hp < 0.0 && t > part.from) {
            part.from = t;
            part.fromEdge = f;
          } else if (hp > 0.0 && t < part.to) {
            part.to = t;
            part.toEdge = f;
          }
        }
        if (part.from < part.to) {
          part.cover = j;
          covered.push_back(part);
        }
      }
      // The pieces of [0, 1] outside the covered parts, from crossing to crossing.
      std::sort(covered.begin(), covered.end(),
                [](const CoveredPart& x, const CoveredPart& y) { return x.from < y.from; });
      const auto pointAt = [&](std::size_t cover, std::size_t edge, double t) {
        const Eigen::Vector2d estimate = p + t * pq;
        return edge == kNoEdge ? (t <= 0.0 ? p : q) : crossing(self, {cover, edge}, estimate);
      };
      double start = 0.0;
      Eigen::Vector2d startPoint = p;
      for (const CoveredPart& part : covered) {
        if (part.from > start) {
          out.addSegment(startPoint, pointAt(part.cover, part.fromEdge, part.from), sign);
        }
        if (part.to > start) {
          start = part.to;
          startPoint = pointAt(part.cover, part.toEdge, part.to);
        }
        if (start >= 1.0) break;
      }
      if (start < 1.0) out.addSegment(startPoint, q, sign);
    }
  }
  if (close(first, 1e-11 * std::max(1.0, (high - low).maxCoeff()), sign, out)) return true;
  out.truncateSegments(first);
  return false;
}

bool UnionOutline::close(std::size_t first, double tolerance, double sign, VisibleRings& out) {
  // Pieces meet where an edge's own vertex ends one and starts the next, or at the crossing of
  // two edges computed once: the same point to the bit. Where the choice between two edges
  // along one line changes hands, where a vertex lies on another shadow's edge, or where a
  // shadow's edge along S''s border lies just past the clip's slack while another's lies
  // within it, an end may miss every start by rounding. The gap would count: each piece's
  // term is a triangle from the foot of x, and at higher degrees, the foot far outside the
  // source, the basis there is thousands of times its size on the source, so a gap of 1e-15
  // shows at 1e-11. A short piece from such an end to the nearest unmatched start closes the
  // outline (the region changes by slivers of that width); an end with no start within
  // `tolerance` fails the outline.
  const std::size_t count = out.segmentCount();
  // First a check that costs little: the starts and the ends are the same points, as many
  // times, if the sum of a hash of each start's coordinates (modulo 2^64) equals that of the
  // ends' (collisions aside: 2^-64).
  const auto hash = [](const Eigen::Vector2d& point) {
    const auto mix = [](std::uint64_t z) {  // splitmix64's finaliser
      z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
      z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
      return z ^ (z >> 31);
    };
    // + 0.0: -0 and +0 are one point.
    return mix(std::bit_cast<std::uint64_t>(point.x() + 0.0) ^
               mix(std::bit_cast<std::uint64_t>(point.y() + 0.0)));
  };
  std::uint64_t balance = 0;
  for (std::size_t s = first; s < count; ++s) {
    balance += hash(out.segmentStart(s)) - hash(out.segmentEnd(s));
  }
  if (balance == 0) return true;
  std::vector<std::pair<Eigen::Vector2d, std::size_t>>& starts = starts_;
  std::vector<std::pair<Eigen::Vector2d, std::size_t>>& ends = ends_;
  starts.clear();
  ends.clear();
  for (std::size_t s = first; s < count; ++s) {
    starts.push_back({out.segmentStart(s), s});
    ends.push_back({out.segmentEnd(s), s});
  }
  const auto before = [](const std::pair<Eigen::Vector2d, std::size_t>& a,
                         const std::pair<Eigen::Vector2d, std::size_t>& b) {
    return a.first.x() < b.first.x() || (a.first.x() == b.first.x() && a.first.y() < b.first.y());
  };
  std::sort(starts.begin(), starts.end(), before);
  std::sort(ends.begin(), ends.end(), before);
  // Match equal points (a merge of the two sorted lists); the unmatched stay, marked by
  // their index, the matched get kNoEdge.
  std::size_t a = 0, b = 0;
  while (a < starts.size() && b < ends.size()) {
    if (starts[a].first == ends[b].first) {
      starts[a++].second = kNoEdge;
      ends[b++].second = kNoEdge;
    } else if (before(starts[a], ends[b])) {
      ++a;
    } else {
      ++b;
    }
  }
  for (auto& [end, endIndex] : ends) {
    if (endIndex == kNoEdge) continue;
    double nearest = tolerance;
    std::size_t chosen = kNoEdge;
    for (std::size_t k = 0; k < starts.size(); ++k) {
      if (starts[k].second == kNoEdge) continue;
      const double distance = (starts[k].first - end).cwiseAbs().maxCoeff();
      if (distance <= nearest) {
        nearest = distance;
        chosen = k;
      }
    }
    if (chosen == kNoEdge) return false;
    out.addSegment(end, starts[chosen].first, sign);
    starts[chosen].second = kNoEdge;
    endIndex = kNoEdge;
  }
  return true;
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
