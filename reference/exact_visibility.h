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
// integral over the union of the shadows. A shadow that overlaps no other (separating-axis
// test) counts as it is. Overlapping ones count by the outline of their union (ShadowUnion):
// the pieces of their edges that no other shadow covers, found by clipping each edge to each
// convex shadow; both inner integrals are sums of one term per edge, so the pieces need not
// be joined into polygons. Where the pieces do not close up, the union is formed by the Vatti
// clipper of Clipper (libpolyclipping, exact integer arithmetic on coordinates scaled by 2^44
// in the source's unit square), which also serves as the check of the outline in the tests.
//
// Occluders are culled once per link against the shaft, the convex hull of the receiver's and
// the source's corners: a polygon entirely outside one face plane of the hull blocks no
// segment between them.
#pragma once

#include <polyclipping/clipper.hpp>

#include <Eigen/Core>
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include "kernel/coupling.h"

namespace radquad {

// A closed polygon in the source's parameter square (u, v), orientation significant:
// counter-clockwise (positive area) rings add, clockwise ones subtract.
using SourceRing = std::vector<Eigen::Vector2d>;

// What x sees: integrate f over V as sum_r sign(r) * (signed integral of f over ring(r)),
// r < count(), plus the pieces of an outline: sum_s segmentSign(s) * (the contour term of
// the edge segmentStart(s) -> segmentEnd(s)), s < segmentCount(). Both integrals the gold
// takes (Lambert's formula and the polar one) are sums of one term per edge, so a region
// bounded by pieces that close up only together (the outline of the shadows' union, cut at
// the points where the shadows cross) needs no rings. The storage is kept across clear()
// so that a thread reuses it.
class VisibleRings {
 public:
  std::size_t count() const { return count_; }
  bool empty() const { return count_ == 0 && segmentCount_ == 0; }
  const SourceRing& ring(std::size_t r) const { return rings_[r]; }
  double sign(std::size_t r) const { return signs_[r]; }
  void setSign(std::size_t r, double sign) { signs_[r] = sign; }
  void clear() {
    count_ = 0;
    segmentCount_ = 0;
  }
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

  std::size_t segmentCount() const { return segmentCount_; }
  // Drops the segments from `count` on.
  void truncateSegments(std::size_t count) { segmentCount_ = std::min(count, segmentCount_); }
  const Eigen::Vector2d& segmentStart(std::size_t s) const { return segmentEnds_[2 * s]; }
  const Eigen::Vector2d& segmentEnd(std::size_t s) const { return segmentEnds_[2 * s + 1]; }
  double segmentSign(std::size_t s) const { return segmentSigns_[s]; }
  void addSegment(const Eigen::Vector2d& start, const Eigen::Vector2d& end, double sign) {
    if (segmentCount_ == segmentSigns_.size()) {
      segmentEnds_.resize(2 * segmentCount_ + 2);
      segmentSigns_.push_back(0.0);
    }
    segmentEnds_[2 * segmentCount_] = start;
    segmentEnds_[2 * segmentCount_ + 1] = end;
    segmentSigns_[segmentCount_++] = sign;
  }

 private:
  std::vector<SourceRing> rings_;
  std::vector<double> signs_;
  std::size_t count_ = 0;
  std::vector<Eigen::Vector2d> segmentEnds_;  // start, end of each segment
  std::vector<double> segmentSigns_;
  std::size_t segmentCount_ = 0;
};

struct ExactVisibilityStatistics {
  std::size_t candidateOccluders = 0;  // after the shaft cull
  std::size_t unions = 0;              // points whose shadows needed a polygon union
  std::size_t unionsByClipper = 0;     // of those, the ones Clipper formed
};

// How the union of overlapping shadows is subtracted (ExactVisibility).
enum class ShadowUnion {
  // Its outline, as the pieces of the shadows' edges that no other shadow covers (segments;
  // the default: the fewest edges, and no polygon formed).
  outline,
  // Inclusion-exclusion over the shadows' intersections (convex rings, more edges than the
  // outline), Clipper beyond 64 of them or where a ring has an edge too short to cut by.
  inclusionExclusion,
  // Clipper's union, as rings (exact integer arithmetic on a grid of 2^-44).
  clipper,
};

// The outline of the union of convex counter-clockwise rings lying inside a convex
// counter-clockwise `border` ring (in the exact gold: the overlapping shadows, inside S'), as
// the pieces of the rings' edges that no other ring covers, in their rings' direction: what
// Lambert's formula and the polar integral need, without forming polygons (details in
// exact_visibility.cpp). Scratch storage is kept from call to call.
class UnionOutline {
 public:
  // The rings rings[i], i in `members`, with their boxes bounds[i] (low u, low v, high u,
  // high v) and, per vertex, onBorder[i][v]: bit s set where the vertex lies on the line of
  // the border's edge s (as the caller's clip placed it; 0 where not known). Adds the pieces
  // to `out` with sign `sign`; false, and `out` as it was, where they do not close up.
  bool add(const std::vector<SourceRing>& rings, const std::vector<std::size_t>& members,
           const std::vector<Eigen::Vector4d>& bounds,
           const std::vector<std::vector<std::uint32_t>>& onBorder, const SourceRing& border,
           double sign, VisibleRings& out);

 private:
  // Closes the pieces from segment `first` on: every end meets a start.
  bool close(std::size_t first, double tolerance, double sign, VisibleRings& out);

  // The parts [from, to] of one ring's edge that ring `cover` covers, and the edges of
  // `cover` they begin and end on (kNoEdge: the covered edge's own end).
  static constexpr std::size_t kNoEdge = std::size_t(-1);
  struct CoveredPart {
    double from, to;
    std::size_t fromEdge, toEdge;
    std::size_t cover = 0;
  };
  std::vector<CoveredPart> covered_;
  // Per ring: (edge vector, squared length, the edge of the border it runs along or -1).
  std::vector<std::vector<Eigen::Vector4d>> edgeLines_;
  // A ring's edge along edge `side` of the border, from parameter `from` to `to` along it;
  // the border's edges whose lines its start and end lie on (bits, as in add()).
  struct BorderPart {
    std::size_t side;
    double from, to;
    Eigen::Vector2d start, end;
    std::uint32_t startOn, endOn;
  };
  std::vector<BorderPart> borderParts_, mergedBorder_;
  std::vector<std::pair<Eigen::Vector2d, std::size_t>> starts_, ends_;  // close()'s
};

class ExactVisibility {
 public:
  // Keeps references to the link's patches and occluder scene; culls the occluders.
  explicit ExactVisibility(const Link& link, ShadowUnion method = ShadowUnion::outline);

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
  // Subtracts the union of the shadows that overlap another by its outline's pieces (out's
  // first ring is S'); false (and `out` as it was) where the pieces do not close up (then
  // Clipper forms the union).
  bool subtractOutline(std::size_t shadowCount, VisibleRings& out);
  // Subtracts it by Clipper's union.
  void subtractClipperUnion(std::size_t shadowCount, VisibleRings& out);

  const Link& link_;
  ShadowUnion method_;
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
  // Per shadow: its clipped occluder polygon in 3D (in the ring's order), the candidate it
  // comes from, and per vertex the planes through x and S''s edges it lies on (bit s for
  // edge s; formed for the outline only).
  std::vector<std::vector<Eigen::Vector3d>> shadowPolygons_;
  std::vector<std::size_t> shadowCandidate_;
  std::vector<std::vector<std::uint32_t>> shadowSides_;
  std::vector<int> pyramidSide_;  // per pyramid plane, the edge of S' it stands on, or -1
  std::vector<Eigen::Vector4d> shadowBounds_;
  std::vector<char> overlaps_;  // per shadow: whether it overlaps another
  // Inclusion-exclusion over the overlapping shadows: their indices, and per depth the
  // intersection of the shadows chosen so far.
  std::vector<std::size_t> overlapping_;
  std::vector<SourceRing> intersections_;
  std::vector<Eigen::Vector4d> intersectionBounds_;  // their boxes, as shadowBounds_
  SourceRing scratchRing_;
  UnionOutline outline_;
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
