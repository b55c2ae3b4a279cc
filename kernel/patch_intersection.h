// Whether two patches interpenetrate: their interiors share a segment (they cross) or, in one
// plane, a region of positive area (they overlap or coincide). Touching along an edge or at a
// corner, or an edge lying on the other patch (a block standing on a floor), is not
// interpenetration: such links are legal, with a singular but integrable kernel.
//
// Between interpenetrating patches the irradiance kernel has a non-integrable singularity
// along the shared set (|x - x'| -> 0 with both cosines positive on one side), so no rule
// can integrate such a link; inputs are checked with this before any work.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "kernel/patch.h"

namespace radquad {

// A description of how a and b interpenetrate ("cross along a segment of length L",
// "overlap in their common plane over an area A"), or nothing when they do not. Lengths and
// areas below 1e-9 of the patches' size are treated as touching.
std::optional<std::string> patchesInterpenetrate(const Patch& a, const Patch& b);

// Whether a convex polygon (an occluder: a parallelogram's corners or a triangle) crosses the
// patch's interior: it has vertices strictly on both sides of the patch's plane, and the
// segment where it meets that plane passes through the patch by more than 1e-9 of its size.
// Touching (a vertex or an edge on the plane) is not crossing.
bool polygonCrossesPatch(const std::vector<Eigen::Vector3d>& polygon, const Patch& patch);

// Whether `element` has corners strictly on both sides of `plane`'s plane (by more than 1e-9
// of the square root of the larger area).
bool straddlesPlane(const Patch& plane, const Patch& element);
// Whether either patch has corners strictly on both sides of the other's plane: the clamped
// cosine then cuts the pair, and the kernel is discontinuous inside the link (a block face
// and the floor it stands on, a wall and a light whose centre lies behind it). Estimates
// from the patches' centres can see nothing there, and product rules converge slowly.
bool cutByTangentPlane(const Patch& receiver, const Patch& source);

// The Euclidean distance between two parallelograms (0 when they touch or cross): the least
// of the distances from each one's corners to the other and between their edges.
double patchDistance(const Patch& a, const Patch& b);

// The Euclidean distance between the segment [a, b] and a parallelogram (0 when the segment
// touches or crosses it).
double segmentToPatchDistance(const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                              const Patch& patch);

// A link is near-singular when its patches are closer than kNearSingularRatio times the
// shorter side of the smaller one: the kernel 1/r^2 then varies over the link far faster than
// any fixed product rule resolves (opposed unit squares 0.01 apart: FullGauss gives a form
// factor of 394), and a rule's result there is not to be trusted.
inline constexpr double kNearSingularRatio = 0.25;
// distance / (shorter side of the patch with the smaller area).
double nearnessRatio(const Patch& a, const Patch& b);

}  // namespace radquad
