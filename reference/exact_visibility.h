// Exact visibility of a source patch from a receiver point, as polygons (docs/design.md,
// "The exact gold").
//
// From a point x with unit normal n_r, the part of the source S that x sees and that faces
// it is
//   S' = S ∩ {y : n_r . (y - x) >= 0}             (the clamped cosine at x: a clip, not a cut-off)
//   V  = S' \ (P_1 ∪ ... ∪ P_k),                   P_i = the shadow of occluder i on S' from x,
// empty when x lies on or behind the source's plane (the clamped cosine at the source). A
// shadow is the central projection from x onto the source's plane of the part of an occluder
// polygon inside the pyramid with apex x over S' (clipped in 3D, so every shadow lies inside
// S' and is convex). Integrals over V are then taken as the integral over S' minus the
// integral over the union of the shadows; the union is formed only when two shadows overlap
// (separating-axis test), with the Vatti clipper of Clipper (libpolyclipping, exact integer
// arithmetic on coordinates scaled by 2^44 in the source's unit square).
//
// Occluders are culled once per link against the shaft, the convex hull of the receiver's and
// the source's corners: a polygon entirely outside one face plane of the hull blocks no
// segment between them.
#pragma once

#include <polyclipping/clipper.hpp>

#include <Eigen/Core>
#include <algorithm>
#include <cstddef>
#include <utility>
#include <vector>

#include "kernel/coupling.h"

namespace radquad {

// A closed polygon in the source's parameter square (u, v), orientation significant:
// counter-clockwise (positive area) rings add, clockwise ones subtract.
using SourceRing = std::vector<Eigen::Vector2d>;

// What x sees: integrate f over V as sum_r sign(r) * (signed integral of f over ring(r)),
// r < count(). The rings' storage is kept across clear() so that a thread reuses it.
class VisibleRings {
 public:
  std::size_t count() const { return count_; }
  bool empty() const { return count_ == 0; }
  const SourceRing& ring(std::size_t r) const { return rings_[r]; }
  double sign(std::size_t r) const { return signs_[r]; }
  void setSign(std::size_t r, double sign) { signs_[r] = sign; }
  void clear() { count_ = 0; }
  // A new empty ring of the given sign (+1 for S', -1 for the rings of the shadows' union).
  SourceRing& add(double sign) {
    if (count_ == rings_.size()) {
      rings_.emplace_back();
      signs_.push_back(0.0);
    }
    rings_[count_].clear();
    signs_[count_] = sign;
    return rings_[count_++];
  }
  void add(const SourceRing& ring, double sign) { add(sign) = ring; }
  // Drops the first ring (S', the source in front of x: what is left is minus the shadows'
  // union, ExactVisibility); the rings keep their order and storage.
  void dropFirst() {
    if (count_ == 0) return;
    std::rotate(rings_.begin(), rings_.begin() + 1, rings_.begin() + std::ptrdiff_t(count_));
    std::rotate(signs_.begin(), signs_.begin() + 1, signs_.begin() + std::ptrdiff_t(count_));
    --count_;
  }
  // Drops the rings from `count` on (their storage is kept).
  void truncate(std::size_t count) { count_ = std::min(count, count_); }

 private:
  std::vector<SourceRing> rings_;
  std::vector<double> signs_;
  std::size_t count_ = 0;
};

struct ExactVisibilityStatistics {
  std::size_t candidateOccluders = 0;  // after the shaft cull
  std::size_t unions = 0;              // points whose shadows needed a polygon union
};

class ExactVisibility {
 public:
  // Keeps references to the link's patches and occluder scene; culls the occluders.
  // Overlapping shadows: their union by inclusion-exclusion over their intersections (convex
  // rings, more edges than the union's outline: cheaper where each edge costs little, as in
  // Lambert's formula), or by Clipper alone (`inclusionExclusion` false: fewer edges, for
  // the polar inner integral, whose edges cost more).
  explicit ExactVisibility(const Link& link, bool inclusionExclusion = true);

  // The visible part of the source from x (on the receiver, normal link.receiver.normal).
  // Thread-compatible: one object per thread, or calls from one thread at a time.
  void visibleRings(const Eigen::Vector3d& x, VisibleRings& out);

  const ExactVisibilityStatistics& statistics() const { return statistics_; }
  std::size_t candidateCount() const { return candidates_.size(); }
  // The occluder polygons in the link's shaft (the only ones that can block it).
  const std::vector<std::vector<Eigen::Vector3d>>& candidates() const { return candidates_; }

 private:
  // Subtracts the union of the shadows that overlap another (overlaps_) by inclusion-exclusion
  // over their intersections; false (and `out` as it was) when Clipper must form it.
  bool subtractOverlapping(std::size_t shadowCount, VisibleRings& out);

  const Link& link_;
  bool inclusionExclusion_;
  Eigen::Vector3d dualU_, dualV_;  // (y - origin) . dualU = u for y in the source's plane
  std::vector<std::vector<Eigen::Vector3d>> candidates_;
  std::vector<double> candidateReach_;  // polygonReach of each candidate
  ExactVisibilityStatistics statistics_;
  // Scratch.
  std::vector<Eigen::Vector3d> clipA_, clipB_, front_;
  std::vector<Eigen::Vector4d> pyramid_;
  std::vector<double> slack_;  // the pyramid planes' slacks for one candidate
  std::vector<std::pair<double, double>> planeNorms_;  // per plane: |normal|_1, |offset|
  std::vector<std::size_t> cutting_;  // the planes that cut one candidate
  std::vector<SourceRing> shadows_;  // only the first ones of a call are its shadows
  std::vector<Eigen::Vector4d> shadowBounds_;
  std::vector<char> overlaps_;  // per shadow: whether it overlaps another
  // Inclusion-exclusion over the overlapping shadows: their indices, and per depth the
  // intersection of the shadows chosen so far.
  std::vector<std::size_t> overlapping_;
  std::vector<SourceRing> intersections_;
  std::vector<Eigen::Vector4d> intersectionBounds_;  // their boxes, as shadowBounds_
  SourceRing scratchRing_;
  std::vector<std::pair<std::size_t, std::size_t>> setStack_;
  ClipperLib::Paths clipperPaths_, clipperUnion_;
};

// The rounding of a height normal . p + offset over points p whose coordinates are at most
// `reach` in magnitude: 64 ulps of the terms' sizes. Heights within it are taken as 0.
double planeSlack(const Eigen::Vector3d& normal, double offset, double reach);

// The largest coordinate magnitude of a polygon's vertices.
double polygonReach(const std::vector<Eigen::Vector3d>& polygon);

// Sutherland-Hodgman clip of a convex polygon (as a vertex list) to the half-space
// plane(p) >= 0 with plane(p) = normal . p + offset; `out` receives the clipped polygon.
// A vertex whose height is within `slack` of 0 lies on the plane: it is kept, and no
// crossing is made at it, so no vertex is repeated, and a polygon lying in the plane up to
// rounding is kept whole (not cut along lines set by rounding). Without `slack`, the
// polygon's planeSlack.
void clipConvexPolygon(const std::vector<Eigen::Vector3d>& polygon, const Eigen::Vector3d& normal,
                       double offset, double slack, std::vector<Eigen::Vector3d>& out);
void clipConvexPolygon(const std::vector<Eigen::Vector3d>& polygon, const Eigen::Vector3d& normal,
                       double offset, std::vector<Eigen::Vector3d>& out);

// The planes (normal, offset) of the convex hull of `points`, with normals pointing outwards;
// points on a face count as inside. Brute force over point triples: for a handful of points.
std::vector<Eigen::Vector4d> convexHullPlanes(const std::vector<Eigen::Vector3d>& points);

// Whether two convex counter-clockwise rings share interior points. Repeated vertices are
// allowed; an edge shorter than 1e-8 of the two rings' extent is not tried as a separating
// axis, so the answer errs towards "overlap" (a pair then goes to the union, which is exact).
bool convexRingsOverlap(const SourceRing& a, const SourceRing& b);

// Signed area of a ring in the plane (positive when counter-clockwise).
double ringArea(const SourceRing& ring);

// The intersection of two convex counter-clockwise rings: `a` clipped to the inner side of
// every edge of `b` (Sutherland-Hodgman), into `out` (`scratch` is working storage). May come
// out with fewer than 3 vertices or no area when they only touch.
void intersectConvexRings(const SourceRing& a, const SourceRing& b, SourceRing& out,
                          SourceRing& scratch);

}  // namespace radquad
