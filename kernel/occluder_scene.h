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

// A batch of segments in structure-of-arrays form (single precision, as Embree traces).
struct SegmentBatch {
  std::vector<float> originX, originY, originZ;
  std::vector<float> directionX, directionY, directionZ;

  std::size_t size() const { return originX.size(); }
  void clear();
  void reserve(std::size_t count);
  void push(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction);
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
  RTCScene handle() const { return scene_; }

  // For each segment k, writes 1 to visible[k] when nothing blocks it, else 0.
  // Traced in packets of 16 with rtcOccluded16. Thread-safe after commit().
  void testSegments(const SegmentBatch& segments, std::uint8_t* visible) const;
  bool segmentVisible(const Eigen::Vector3d& from, const Eigen::Vector3d& to) const;

 private:
  RTCScene scene_ = nullptr;
  std::size_t geometryCount_ = 0;
  std::size_t primitiveCount_ = 0;
  bool committed_ = false;
};

// The process-wide Embree device (created on first use).
RTCDevice embreeDevice();

}  // namespace radquad
