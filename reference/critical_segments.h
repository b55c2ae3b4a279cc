// The critical segments of a link on its receiver (docs/design.md, "The gold"): where the
// part of the source that a receiver point x sees changes shape.
//
// The inner integral I_b(x) of the exact gold is analytic in x except where the visible
// polygon V(x) changes its combinatorial structure. With the occluders clipped to the slab in
// front of both patches' planes, V(x) changes shape when
//   - a vertex P of one polygon (an occluder, or the source clipped by the receiver's plane)
//     is seen from x exactly on an edge E of another (a shadow vertex crosses a source edge,
//     a source vertex enters a shadow, a shadow vertex crosses another shadow's edge): x lies
//     in the plane through P and E, on the part of it from which the nearer of the two is
//     seen in front of the farther; on the receiver's plane that part is a segment;
//   - x crosses the source's plane (the clamped cosine at the source), or an occluder's plane
//     (seen edge-on, its shadow has no area and grows as the distance from that plane);
// (The clamped cosine at x clips the source by the receiver's own plane, the same for every
// x: no event.) The events left out are those of three edges (two shadow edges crossing
// on a third edge), which lie on curves, not lines; the adaptive integration resolves them.
//
// Segments are in the receiver's parameters (s, t), clipped to the unit square. Between
// them, I_b is analytic, so a Gauss rule over each piece converges exponentially.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "kernel/patch.h"

namespace radquad {

struct ReceiverSegment {
  Eigen::Vector2d a, b;  // endpoints in the receiver's (s, t), inside [0, 1]^2
};

// `occluders`: the convex occluder polygons that can block the link (its shaft's).
std::vector<ReceiverSegment> criticalSegments(
    const Patch& receiver, const Patch& source,
    const std::vector<std::vector<Eigen::Vector3d>>& occluders);

// Where an occluder meets the receiver along a segment (it stands on the receiver or passes
// through it), in (s, t), clipped to the unit square. On either side of such a segment the
// occluder hides a different half of what lies beyond its plane, so the inner integral
// jumps there (criticalSegments has the segment, on its occluder's plane line).
std::vector<ReceiverSegment> contactSegments(
    const Patch& receiver, const std::vector<std::vector<Eigen::Vector3d>>& occluders);

// The t of every segment crossing the line s = const (segments along t excluded: they are
// breakpoints of the outer integral), with 0 and 1.
std::vector<double> crossingsAt(const std::vector<ReceiverSegment>& segments, double s);

}  // namespace radquad
