// Visibility V(x,x') between points of two patches, by Embree 3 occlusion rays against a
// scene of occluders: parallelograms (from JSON) and triangle meshes (built in code).
// A link's own two patches are never part of its occluder scene; segments are also
// shortened by a relative epsilon at both ends so that geometry touching an end point
// (a block standing on a floor) does not block it.
#pragma once

#include <embree3/rtcore.h>

#include <Eigen/Core>
#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include "kernel/patch.h"

namespace radquad {

// Segments are tested for t in [kSegmentEpsilon, 1 - kSegmentEpsilon] of origin + t direction.
inline constexpr float kSegmentEpsilon = 1e-5f;

// A batch of segments stored directly as Embree 16-wide ray packets, so they are traced in
// place with no copy: segment k lives in lane k % 16 of packet k / 16.
class SegmentBatch {
 public:
  std::size_t size() const { return count_; }
  void clear() { count_ = 0; }
  // Grows or shrinks to `count` segments; the contents of new segments are unspecified.
  void resize(std::size_t count);
  void push(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction);
  void set(std::size_t k, double ox, double oy, double oz, double dx, double dy, double dz) {
    RTCRay16& packet = packets_[k >> 4];
    const std::size_t lane = k & 15;
    packet.org_x[lane] = float(ox);
    packet.org_y[lane] = float(oy);
    packet.org_z[lane] = float(oz);
    packet.dir_x[lane] = float(dx);
    packet.dir_y[lane] = float(dy);
    packet.dir_z[lane] = float(dz);
    packet.tfar[lane] = 1.0f - kSegmentEpsilon;  // Embree sets it to -inf when blocked
  }
  // After OccluderScene::trace: whether segment k was unobstructed.
  bool visible(std::size_t k) const { return packets_[k >> 4].tfar[k & 15] >= 0.0f; }

  std::size_t packetCount() const { return (count_ + 15) / 16; }
  RTCRay16* packets() { return packets_.data(); }
  const RTCRay16& packet(std::size_t p) const { return packets_[p]; }

 private:
  std::vector<RTCRay16> packets_;
  std::size_t count_ = 0;
};

class OccluderScene {
 public:
  OccluderScene();
  ~OccluderScene();
  OccluderScene(const OccluderScene&) = delete;
  OccluderScene& operator=(const OccluderScene&) = delete;

  // Adds one parallelogram (two triangles' worth of surface, both sides block).
  // Returns the Embree geometry id.
  unsigned addParallelogram(const Patch& patch);
  // Adds a triangle mesh; every index must be < vertices.size().
  unsigned addTriangleMesh(const std::vector<Eigen::Vector3d>& vertices,
                           const std::vector<std::array<std::uint32_t, 3>>& triangles);
  // Builds the acceleration structure; must be called after the last add and before tracing.
  void commit();

  bool empty() const { return geometryCount_ == 0; }
  std::size_t geometryCount() const { return geometryCount_; }
  std::size_t primitiveCount() const { return primitiveCount_; }
  // Every primitive added so far as a convex polygon in double precision (a parallelogram's
  // four corners, a triangle's three), in the order added: the geometry that exact
  // visibility (reference/exact_visibility.h) projects, beside the float copy Embree traces.
  const std::vector<std::vector<Eigen::Vector3d>>& polygons() const { return polygons_; }
  RTCScene handle() const { return scene_; }

  // Traces every segment of the batch in place (rtcOccluded16 on its packets); afterwards
  // segments.visible(k) tells whether segment k is unobstructed. Thread-safe after commit().
  void trace(SegmentBatch& segments) const;
  // The same, writing 1 (unobstructed) or 0 (blocked) to visible[k].
  void testSegments(const SegmentBatch& segments, std::uint8_t* visible) const;
  bool segmentVisible(const Eigen::Vector3d& from, const Eigen::Vector3d& to) const;

  // The geometry hit first by the ray origin + t direction, t > 0, and that t; -1 when the
  // ray hits nothing. Geometry ids count from 0 in the order of the add calls.
  int closestHit(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction, double& t) const;

 private:
  RTCScene scene_ = nullptr;
  std::size_t geometryCount_ = 0;
  std::size_t primitiveCount_ = 0;
  bool committed_ = false;
  std::vector<std::vector<Eigen::Vector3d>> polygons_;
};

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

}  // namespace radquad
