// The ray-casting scene of the Monte Carlo path tracer (path_tracer.h): every patch of a
// radiosity scene as one Embree quad whose geometry id is the patch's index. Both sides of a
// quad stop rays; which side was hit is left to the caller (the patch normals).
//
// Rays ignore chosen patches exactly, by geometry id, through an Embree context filter
// function: a first-hit ray from a point on patch p ignores p, and a shadow ray from x on p
// to y on an emitter e ignores p and e. Nothing else is excluded and segments are not
// shortened, so no gap between other patches can leak light.
//
// This class shares no code with the solver's visibility (kernel/occluder_scene.h,
// radiosity/visibility.h); only the process-wide Embree device is common.
#pragma once

#include <Eigen/Core>
#include <cstdint>

#include "radiosity/scene.h"

// Embree's scene type, declared only (its header stays in trace_scene.cpp).
struct RTCSceneTy;

namespace radquad {

class TraceScene {
 public:
  // Throws std::runtime_error when the Embree library lacks filter functions.
  explicit TraceScene(const Scene& scene);
  ~TraceScene();
  TraceScene(const TraceScene&) = delete;
  TraceScene& operator=(const TraceScene&) = delete;

  // The patch hit first by origin + t direction, t in (0, inf), ignoring patch `ignore`, with
  // that t (direction need not be unit length); -1 when the ray leaves the scene.
  // Thread-safe.
  int firstHit(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction, int ignore,
               double& t) const;

  // Whether the open segment from `from` to `to` crosses no patch other than `ignoreA` and
  // `ignoreB`. Thread-safe.
  bool unobstructed(const Eigen::Vector3d& from, const Eigen::Vector3d& to, int ignoreA,
                    int ignoreB) const;

 private:
  RTCSceneTy* scene_ = nullptr;
};

}  // namespace radquad
