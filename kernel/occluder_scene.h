// Visibility V(x,x') between points of two patches, by Embree 3 occlusion rays against a
// scene of occluders: parallelograms (from JSON) and triangle meshes (built in code).
// A link's own two patches are never part of its occluder scene; segments are also
// shortened by a relative epsilon at both ends so that geometry touching an end point
// (a block standing on a floor) does not block it.
//
// The one place where rays are staged, traced and applied: every coupling path stages its
// segments in a SegmentBatch, and OccluderScene::traceMasking traces them and zeroes the
// kernel values of the blocked ones. Embree's own types stay in occluder_scene.cpp (and
// kernel/embree_device.h, for the few .cpp files that build Embree scenes themselves).
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include "kernel/patch.h"

// Embree's scene type, declared only (its header stays in the .cpp files).
struct RTCSceneTy;

namespace radquad {

// Segments are tested for t in [kSegmentEpsilon, 1 - kSegmentEpsilon] of origin + t direction.
inline constexpr float kSegmentEpsilon = 1e-5f;

// Sixteen segments in the layout of Embree's 16-wide ray packet (RTCRay16; occluder_scene.cpp
// checks every field's offset), so that a batch is traced in place with no copy. Embree
// writes only tfar: -inf in the lanes it finds blocked.
struct alignas(64) SegmentPacket {
  float org_x[16], org_y[16], org_z[16], tnear[16];
  float dir_x[16], dir_y[16], dir_z[16], time[16];
  float tfar[16];
  std::uint32_t mask[16], id[16], flags[16];
};

// A batch of segments stored as 16-wide packets: segment k lives in lane k % 16 of packet
// k / 16.
class SegmentBatch {
 public:
  std::size_t size() const { return count_; }
  void clear() { count_ = 0; }
  // Grows or shrinks to `count` segments; the contents of new segments are unspecified.
  void resize(std::size_t count);
  void push(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction);
  void set(std::size_t k, double ox, double oy, double oz, double dx, double dy, double dz) {
    SegmentPacket& packet = packets_[k >> 4];
    const std::size_t lane = k & 15;
    packet.org_x[lane] = float(ox);
    packet.org_y[lane] = float(oy);
    packet.org_z[lane] = float(oz);
    packet.dir_x[lane] = float(dx);
    packet.dir_y[lane] = float(dy);
    packet.dir_z[lane] = float(dz);
    packet.tfar[lane] = 1.0f - kSegmentEpsilon;  // Embree sets it to -inf when blocked
  }
  // Copies segment `from` to slot `to` (to <= from: compacting a batch in order).
  void move(std::size_t from, std::size_t to) {
    const SegmentPacket& source = packets_[from >> 4];
    SegmentPacket& target = packets_[to >> 4];
    const std::size_t f = from & 15, t = to & 15;
    target.org_x[t] = source.org_x[f];
    target.org_y[t] = source.org_y[f];
    target.org_z[t] = source.org_z[f];
    target.dir_x[t] = source.dir_x[f];
    target.dir_y[t] = source.dir_y[f];
    target.dir_z[t] = source.dir_z[f];
    target.tfar[t] = source.tfar[f];
  }
  // Sets the batch to `count` segments from float columns (origin, direction); each column
  // must hold whole packets ((count + 15) / 16 * 16 entries): they are copied 16 at a time.
  void assignColumns(std::size_t count, const float* originX, const float* originY,
                     const float* originZ, const float* directionX, const float* directionY,
                     const float* directionZ);
  // After OccluderScene::trace: whether segment k was unobstructed.
  bool visible(std::size_t k) const { return packets_[k >> 4].tfar[k & 15] >= 0.0f; }

  std::size_t packetCount() const { return (count_ + 15) / 16; }
  // The packets, for code that stages segments itself (the streamed coupling path writes
  // them as it places its points, as set() does).
  SegmentPacket* packets() { return packets_.data(); }

 private:
  std::vector<SegmentPacket> packets_;
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
  // Embree's scene (RTCScene), for kernel/embree_device.h's users.
  RTCSceneTy* handle() const { return scene_; }

  // Traces every segment of the batch in place (rtcOccluded16 on its packets); afterwards
  // segments.visible(k) tells whether segment k is unobstructed. Thread-safe after commit().
  void trace(SegmentBatch& segments) const;
  // Traces the batch and zeroes values[k] for every blocked segment k (a NaN far end counts
  // as blocked); returns how many were blocked.
  std::uint64_t traceMasking(SegmentBatch& segments, double* values) const;
  // The same where segment r belongs to values[owner[r]].
  std::uint64_t traceMasking(SegmentBatch& segments, const std::uint32_t* owner,
                             double* values) const;
  // The same, writing 1 (unobstructed) or 0 (blocked) to visible[k].
  void testSegments(const SegmentBatch& segments, std::uint8_t* visible) const;
  bool segmentVisible(const Eigen::Vector3d& from, const Eigen::Vector3d& to) const;

  // The geometry hit first by the ray origin + t direction, t > 0, and that t; -1 when the
  // ray hits nothing. Geometry ids count from 0 in the order of the add calls.
  int closestHit(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction, double& t) const;

 private:
  RTCSceneTy* scene_ = nullptr;
  std::size_t geometryCount_ = 0;
  std::size_t primitiveCount_ = 0;
  bool committed_ = false;
  std::vector<std::vector<Eigen::Vector3d>> polygons_;
};

}  // namespace radquad
