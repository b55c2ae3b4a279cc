// How ExactVisibility subtracts the union of the shadows that overlap another
// (exact_visibility.h, ShadowUnion): by its outline (the default, union_outline.h), by
// inclusion-exclusion over the shadows' intersections, or as Clipper's union.
#include <polyclipping/clipper.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "reference/exact_visibility.h"

namespace radquad {
namespace {

// Clipper's integer grid on the source's unit square: 2^44 steps (a resolution of 6e-14).
constexpr double kClipperScale = 17592186044416.0;

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
            planeSlackOf(norm, offset, reach)) {
          on |= std::uint32_t(1) << pyramidSide_[k];
        }
      }
      sides.push_back(on);
    }
  }
  return outline_.add(shadows_, overlapping_, shadowBounds_, shadowSides_, out.ring(0), -1.0, out);
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
