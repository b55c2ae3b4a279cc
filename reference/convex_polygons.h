// Convex polygons for the exact gold's visibility (exact_visibility.h): clipping to
// half-spaces with a slack that takes rounding for lying on the plane, the planes of a convex
// hull, and convex rings in the source's parameter square (overlap, area, intersection).
#pragma once

#include <Eigen/Core>
#include <vector>

namespace radquad {

// A closed polygon in the source's parameter square (u, v), orientation significant:
// counter-clockwise (positive area) rings add, clockwise ones subtract.
using SourceRing = std::vector<Eigen::Vector2d>;

// The rounding of a height normal . p + offset over points p whose coordinates are at most
// `reach` in magnitude: 64 ulps of the terms' sizes. Heights within it are taken as 0.
double planeSlack(const Eigen::Vector3d& normal, double offset, double reach);
// The same from the plane's |normal|_1 and |offset| (computed once per plane where many
// polygons are clipped to it).
double planeSlackOf(double normalNorm, double offsetMagnitude, double reach);

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
