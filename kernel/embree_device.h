// For the .cpp files that talk to Embree themselves (kernel/occluder_scene.cpp, the path
// tracer's radiosity/trace_scene.cpp, the ray benchmark): the process-wide device, its error
// check, the one way patches become Embree geometry, and the view of a segment batch as
// Embree's ray packets. No header includes this one, so Embree stays a private dependency.
#pragma once

#include <embree3/rtcore.h>

#include "kernel/occluder_scene.h"
#include "kernel/patch.h"

namespace radquad {

// The process-wide Embree device (created on first use).
RTCDevice embreeDevice();

// Throws ComputationError naming `step` and Embree's message when the last Embree call on
// this thread failed (out of memory, an invalid argument, a failed build); Embree reports
// errors through a callback and a per-thread error code, never by exception.
void checkEmbree(const char* step);

// A committed Embree quad geometry of one parallelogram (corners o, o+a, o+a+b, o+b in float),
// not yet attached to a scene: the one way patches become Embree geometry. Throws
// ComputationError when Embree fails (checkEmbree).
RTCGeometry newParallelogramGeometry(RTCDevice device, const Patch& patch);

// The batch's packets as Embree's (the layouts are one, checked in occluder_scene.cpp).
inline RTCRay16* embreePackets(SegmentBatch& segments) {
  return reinterpret_cast<RTCRay16*>(segments.packets());
}

}  // namespace radquad
