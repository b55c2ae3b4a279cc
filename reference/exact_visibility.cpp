#include "reference/exact_visibility.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

namespace radquad {
namespace {

// Points this close to the apex (relative to x's height over the source plane) are cut: a
// polygon through x itself casts a shadow of zero area.
constexpr double kApexMargin = 1e-12;
// A polygon clipped to the shaft with less area than this share of the larger patch's only
// touches it (occludersInShaft).
constexpr double kShaftAreaRounding = 1e-12;

}  // namespace

ExactVisibility::ExactVisibility(const Link& link, ShadowUnion method)
    : link_(link), method_(method) {
  setDuals();
  if (link.hasOccluders()) cull(link.occluders->polygons(), nullptr);
}

ExactVisibility::ExactVisibility(const Link& link,
                                 const std::vector<std::vector<Eigen::Vector3d>>& polygons,
                                 const std::vector<int>& candidates, ShadowUnion method)
    : link_(link), method_(method) {
  setDuals();
  cull(polygons, &candidates);
}

void ExactVisibility::setDuals() {
  const Patch& source = link_.source;
  const double uu = source.edgeU.dot(source.edgeU), uv = source.edgeU.dot(source.edgeV),
               vv = source.edgeV.dot(source.edgeV);
  const double determinant = uu * vv - uv * uv;
  dualU_ = (vv * source.edgeU - uv * source.edgeV) / determinant;
  dualV_ = (uu * source.edgeV - uv * source.edgeU) / determinant;
}

void ExactVisibility::cull(const std::vector<std::vector<Eigen::Vector3d>>& polygons,
                           const std::vector<int>* indices) {
  std::vector<Eigen::Vector3d> corners;
  for (const auto& c : link_.receiver.corners()) corners.push_back(c);
  for (const auto& c : link_.source.corners()) corners.push_back(c);
  double scale = 0.0;
  for (const auto& c : corners) scale = std::max(scale, c.cwiseAbs().maxCoeff());
  const std::vector<Eigen::Vector4d> planes = convexHullPlanes(corners);
  // The shaft's interior as half-spaces normal . p + offset >= 0: inside every face of the hull,
  // in front of both patches (where the kernel is positive).
  for (const auto& plane : planes) shaftPlanes_.push_back(-plane);
  for (const Patch* patch : {&link_.receiver, &link_.source}) {
    shaftPlanes_.push_back({patch->normal.x(), patch->normal.y(), patch->normal.z(),
                            -patch->normal.dot(patch->origin)});
  }
  shaftArea_ = std::max(link_.receiver.area, link_.source.area);
  const double tolerance = 1e-9 * scale;
  const std::size_t count = indices ? indices->size() : polygons.size();
  for (std::size_t k = 0; k < count; ++k) {
    const auto& polygon = polygons[indices ? std::size_t((*indices)[k]) : k];
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

std::size_t ExactVisibility::occludersInShaft() const {
  std::size_t count = 0;
  std::vector<Eigen::Vector3d> clipped, next;
  for (const auto& polygon : candidates_) {
    clipped = polygon;
    for (const auto& plane : shaftPlanes_) {
      clipConvexPolygon(clipped, plane.head<3>(), plane[3], next);
      std::swap(clipped, next);
      if (clipped.size() < 3) break;
    }
    if (clipped.size() < 3) continue;
    // A polygon lying in one of the shaft's faces (a wall along its side) touches it only.
    const bool inFace = std::any_of(shaftPlanes_.begin(), shaftPlanes_.end(), [&](const Eigen::Vector4d& plane) {
      const double slack = planeSlack(plane.head<3>(), plane[3], polygonReach(clipped));
      return std::all_of(clipped.begin(), clipped.end(), [&](const Eigen::Vector3d& p) {
        return plane.head<3>().dot(p) + plane[3] <= slack;
      });
    });
    if (inFace) continue;
    Eigen::Vector3d twice = Eigen::Vector3d::Zero();
    for (std::size_t i = 0, n = clipped.size(); i < n; ++i) {
      twice += clipped[i].cross(clipped[(i + 1) % n]);
    }
    // Rounding leaves a sliver of about 1e-16 of the patches' size where a polygon only
    // touches the shaft (a neighbour in the receiver's plane along its edge).
    count += 0.5 * twice.norm() > kShaftAreaRounding * shaftArea_;
  }
  return count;
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
      slack_.push_back(planeSlackOf(norm, offset, reach));
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

}  // namespace radquad
