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
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include "kernel/coupling.h"
#include "reference/convex_polygons.h"
#include "reference/union_outline.h"
#include "reference/visible_rings.h"

namespace radquad {

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

class ExactVisibility {
 public:
  // Keeps references to the link's patches and occluder scene; culls the occluders.
  explicit ExactVisibility(const Link& link, ShadowUnion method = ShadowUnion::outline);
  // The same with the occluders polygons[i], i in `candidates`, instead of link.occluders's.
  ExactVisibility(const Link& link, const std::vector<std::vector<Eigen::Vector3d>>& polygons,
                  const std::vector<int>& candidates, ShadowUnion method = ShadowUnion::outline);

  // The visible part of the source from x (on the receiver, normal link.receiver.normal).
  // Thread-compatible: one object per thread, or calls from one thread at a time.
  void visibleRings(const Eigen::Vector3d& x, VisibleRings& out);

  const ExactVisibilityStatistics& statistics() const { return statistics_; }
  std::size_t candidateCount() const { return candidates_.size(); }
  // The occluder polygons in the link's shaft (the only ones that can block it).
  const std::vector<std::vector<Eigen::Vector3d>>& candidates() const { return candidates_; }
  // How many of them meet the shaft's interior, where the kernel is positive: clipped to every
  // face of the hull and to the front of both patches, a polygon keeps an area (more than
  // 1e-12 of the larger patch's, rounding). The cull above is conservative (a polygon is
  // dropped only when one face plane has it wholly outside); this is exact. With none, no
  // segment between the patches is blocked, and the link sees its whole source from every
  // receiver point.
  std::size_t occludersInShaft() const;

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

  void setDuals();
  // Keeps the polygons (those of `indices`, or all) that meet the link's shaft.
  void cull(const std::vector<std::vector<Eigen::Vector3d>>& polygons,
            const std::vector<int>* indices);

  const Link& link_;
  ShadowUnion method_;
  Eigen::Vector3d dualU_, dualV_;  // (y - origin) . dualU = u for y in the source's plane
  std::vector<std::vector<Eigen::Vector3d>> candidates_;
  std::vector<double> candidateReach_;  // polygonReach of each candidate
  std::vector<Eigen::Vector4d> shaftPlanes_;  // the shaft's interior: normal . p + offset >= 0
  double shaftArea_ = 0.0;  // the larger patch's area
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

}  // namespace radquad
