// The ray-casting scene of the Monte Carlo path tracer (path_tracer.h): every patch of a
// radiosity scene as one Embree quad whose geometry id is the patch's index. Both sides of a
// quad stop rays; which side was hit is left to the caller (the patch normals), except on a
// two-sided surface (below).
//
// Rays ignore chosen patches exactly, by geometry id, through an Embree context filter
// function. A ray leaving a point x of patch p ignores p's plane mates (below), p among them;
// a shadow ray from x on p to y on an emitter e ignores the mates of p and of e. Nothing else
// is excluded and segments are not shortened, so no gap between other patches can leak light.
//
// Plane mates: the patches that lie in p's plane, to within kPlaneMateTolerance times the
// scene's largest coordinate magnitude (every corner of each within that distance of the
// other's plane), and whose bounding boxes, grown by that distance, meet p's. A ray that
// leaves p's plane meets it again nowhere: it can meet a mate only at its own origin (or, a
// mate lying off the plane by d < tolerance, along a grazing direction within d / (distance
// travelled) of the plane), and a segment between two planes meets a mate of either only at
// its ends. So ignoring the mates is exact for mates in the plane, and what they hide from
// a mate off it by d is of the order of d over the scene's size. Without it, a two-sided panel
// made of two coincident, opposite-facing patches (legal in the scene format) stops every ray
// leaving either face at distance zero: both faces read 0. The tolerance is well above the
// rounding of single-precision coordinates and of Embree's intersection (about 1e-7 of the
// largest coordinate), which decides the side of a gap below it at random.
//
// Two-sided surfaces: two opposite-facing mates that cover the same point are one two-sided
// surface there, and a ray arriving at it hits the face that faces it. Embree may report the
// other one (at the same distance, or nearer by less than the tolerance); `firstHit` then
// returns the mate whose front faces the ray and contains the hit point (projected onto its
// plane), where there is one. So a lamp whose dark back is a coincident patch is seen from
// below, and a panel's back-to-back faces are seen from either side.
//
// This class shares no code with the solver's visibility (kernel/occluder_scene.h,
// radiosity/visibility.h); only the process-wide Embree device is common.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "radiosity/scene.h"

// Embree's scene type, declared only (its header stays in trace_scene.cpp).
struct RTCSceneTy;

namespace radquad {

// Plane mates lie within this fraction of the scene's largest coordinate magnitude of each
// other's planes.
inline constexpr double kPlaneMateTolerance = 1e-6;

// For every patch, its plane mates (itself included), in increasing order.
std::vector<std::vector<int>> planeMates(const Scene& scene);

class TraceScene {
 public:
  // Throws std::runtime_error when the Embree library lacks filter functions.
  explicit TraceScene(const Scene& scene);
  ~TraceScene();
  TraceScene(const TraceScene&) = delete;
  TraceScene& operator=(const TraceScene&) = delete;

  // The patch hit first by origin + t direction, t in (0, inf), ignoring the plane mates of
  // patch `from` (none when from < 0), with that t (direction need not be unit length); on a
  // two-sided surface, the face that faces the ray. -1 when the ray leaves the scene.
  // Thread-safe.
  int firstHit(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction, int from,
               double& t) const;

  // Whether the open segment from `from` to `to` crosses no patch other than the plane mates
  // of `patchA` and `patchB`. Thread-safe.
  bool unobstructed(const Eigen::Vector3d& from, const Eigen::Vector3d& to, int patchA,
                    int patchB) const;

  // Whether patches a and b are plane mates.
  bool mates(int a, int b) const;

 private:
  RTCSceneTy* scene_ = nullptr;
  std::vector<Patch> patches_;
  std::vector<std::vector<int>> mates_;
  double tolerance_ = 0.0;  // kPlaneMateTolerance x the largest coordinate magnitude
};

}  // namespace radquad
