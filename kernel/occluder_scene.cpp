#include "kernel/occluder_scene.h"

#include <algorithm>
#include <cstddef>
#include <cstdio>
#include <cstring>
#include <limits>
#include <mutex>
#include <stdexcept>
#include <string>

#include "kernel/embree_device.h"
#include "kernel/input_error.h"
#include "kernel/simd_lanes.h"

// SegmentPacket is RTCRay16, field for field: batches are traced in place.
static_assert(sizeof(radquad::SegmentPacket) == sizeof(RTCRay16));
static_assert(alignof(radquad::SegmentPacket) == alignof(RTCRay16));
#define RADQUAD_SAME_OFFSET(field) \
  static_assert(offsetof(radquad::SegmentPacket, field) == offsetof(RTCRay16, field))
RADQUAD_SAME_OFFSET(org_x);
RADQUAD_SAME_OFFSET(org_y);
RADQUAD_SAME_OFFSET(org_z);
RADQUAD_SAME_OFFSET(tnear);
RADQUAD_SAME_OFFSET(dir_x);
RADQUAD_SAME_OFFSET(dir_y);
RADQUAD_SAME_OFFSET(dir_z);
RADQUAD_SAME_OFFSET(time);
RADQUAD_SAME_OFFSET(tfar);
RADQUAD_SAME_OFFSET(mask);
RADQUAD_SAME_OFFSET(id);
RADQUAD_SAME_OFFSET(flags);
#undef RADQUAD_SAME_OFFSET

namespace radquad {
namespace {

// The first message Embree reported on this thread since the last check (its error callback
// runs on the thread whose call failed; rtcGetDeviceError likewise keeps the first code), so
// that checkEmbree's code and message belong together.
thread_local std::string firstEmbreeMessage;

void reportEmbreeError(void*, RTCError code, const char* message) {
  const std::string text =
      "Embree error " + std::to_string(static_cast<int>(code)) + ": " + (message ? message : "");
  std::fprintf(stderr, "radquad: %s\n", text.c_str());
  if (firstEmbreeMessage.empty()) firstEmbreeMessage = text;
}

[[noreturn]] void embreeFailed(const char* step) {
  checkEmbree(step);
  throw ComputationError(std::string(step) + ": Embree returned no result");
}

}  // namespace

void checkEmbree(const char* step) {
  const RTCError code = rtcGetDeviceError(embreeDevice());
  std::string message = std::move(firstEmbreeMessage);
  firstEmbreeMessage.clear();
  if (code == RTC_ERROR_NONE) return;
  if (message.empty()) message = "Embree error " + std::to_string(static_cast<int>(code));
  throw ComputationError(std::string(step) + ": " + message);
}

RTCDevice embreeDevice() {
  static RTCDevice device = [] {
    RTCDevice created = rtcNewDevice(nullptr);
    if (!created) throw std::runtime_error("cannot create the Embree device");
    rtcSetDeviceErrorFunction(created, reportEmbreeError, nullptr);
    return created;
  }();
  return device;
}

void SegmentBatch::resize(std::size_t count) {
  const std::size_t packets = (count + 15) / 16;
  if (packets > packets_.size()) {
    SegmentPacket fresh;
    for (int lane = 0; lane < 16; ++lane) {
      fresh.org_x[lane] = fresh.org_y[lane] = fresh.org_z[lane] = 0.0f;
      fresh.dir_x[lane] = fresh.dir_y[lane] = fresh.dir_z[lane] = 0.0f;
      fresh.tnear[lane] = kSegmentEpsilon;
      fresh.tfar[lane] = 1.0f - kSegmentEpsilon;
      fresh.time[lane] = 0.0f;
      fresh.mask[lane] = 0xFFFFFFFFu;
      fresh.id[lane] = 0;
      fresh.flags[lane] = 0;
    }
    packets_.resize(packets, fresh);
  }
  count_ = count;
}

void SegmentBatch::assignColumns(std::size_t count, const float* originX, const float* originY,
                                 const float* originZ, const float* directionX,
                                 const float* directionY, const float* directionZ) {
  // Fixed 16-lane copies (the columns hold whole packets; lanes past `count` are traced by
  // no one), and tfar reset: the only field Embree writes. The other fields keep the values
  // resize() gave them.
  resize(count);
  SegmentPacket* __restrict packets = packets_.data();
  constexpr std::size_t kBytes = 16 * sizeof(float);
  for (std::size_t p = 0; p < packetCount(); ++p) {
    SegmentPacket& packet = packets[p];
    const std::size_t start = p * 16;
    std::memcpy(packet.org_x, originX + start, kBytes);
    std::memcpy(packet.org_y, originY + start, kBytes);
    std::memcpy(packet.org_z, originZ + start, kBytes);
    std::memcpy(packet.dir_x, directionX + start, kBytes);
    std::memcpy(packet.dir_y, directionY + start, kBytes);
    std::memcpy(packet.dir_z, directionZ + start, kBytes);
    for (int lane = 0; lane < 16; ++lane) packet.tfar[lane] = 1.0f - kSegmentEpsilon;
  }
}

void SegmentBatch::push(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction) {
  const std::size_t k = count_;
  resize(k + 1);
  set(k, origin.x(), origin.y(), origin.z(), direction.x(), direction.y(), direction.z());
}

OccluderScene::OccluderScene() {
  checkEmbree("before an occluder scene");
  scene_ = rtcNewScene(embreeDevice());
  if (scene_ == nullptr) embreeFailed("creating an occluder scene");
  // Robust traversal: slats and meshes share edges, and a ray through a shared edge must
  // not slip between two triangles.
  rtcSetSceneFlags(scene_, RTC_SCENE_FLAG_ROBUST);
  rtcSetSceneBuildQuality(scene_, RTC_BUILD_QUALITY_HIGH);
  try {
    checkEmbree("setting up an occluder scene");
  } catch (...) {
    rtcReleaseScene(scene_);
    throw;
  }
}

OccluderScene::~OccluderScene() {
  if (scene_) rtcReleaseScene(scene_);
}

RTCGeometry newParallelogramGeometry(RTCDevice device, const Patch& patch) {
  checkEmbree("before a parallelogram geometry");  // no stale error is blamed on this one
  RTCGeometry geometry = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_QUAD);
  if (geometry == nullptr) embreeFailed("creating a parallelogram geometry");
  auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(
      geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), 4));
  if (vertices == nullptr) {
    rtcReleaseGeometry(geometry);
    embreeFailed("allocating a parallelogram's vertices");
  }
  const std::array<Eigen::Vector3d, 4> corners = patch.corners();
  for (int c = 0; c < 4; ++c) {
    for (int axis = 0; axis < 3; ++axis) vertices[3 * c + axis] = float(corners[c][axis]);
  }
  auto* indices = static_cast<unsigned*>(rtcSetNewGeometryBuffer(
      geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT4, 4 * sizeof(unsigned), 1));
  if (indices == nullptr) {
    rtcReleaseGeometry(geometry);
    embreeFailed("allocating a parallelogram's index");
  }
  for (unsigned c = 0; c < 4; ++c) indices[c] = c;
  rtcCommitGeometry(geometry);
  try {
    checkEmbree("committing a parallelogram geometry");
  } catch (...) {
    rtcReleaseGeometry(geometry);
    throw;
  }
  return geometry;
}

unsigned OccluderScene::addParallelogram(const Patch& patch) {
  RADQUAD_REQUIRE(!committed_);
  RTCGeometry geometry = newParallelogramGeometry(embreeDevice(), patch);
  const unsigned id = rtcAttachGeometry(scene_, geometry);
  rtcReleaseGeometry(geometry);
  checkEmbree("adding a parallelogram");
  ++geometryCount_;
  ++primitiveCount_;
  const std::array<Eigen::Vector3d, 4> corners = patch.corners();
  polygons_.emplace_back(corners.begin(), corners.end());
  return id;
}

unsigned OccluderScene::addTriangleMesh(
    const std::vector<Eigen::Vector3d>& vertices,
    const std::vector<std::array<std::uint32_t, 3>>& triangles) {
  RADQUAD_REQUIRE(!committed_);
  for (const auto& triangle : triangles) {
    for (std::uint32_t index : triangle) {
      if (index >= vertices.size()) {
        throw std::invalid_argument("triangle mesh index " + std::to_string(index) +
                                    " is out of range");
      }
    }
  }
  checkEmbree("before a triangle mesh");
  RTCGeometry geometry = rtcNewGeometry(embreeDevice(), RTC_GEOMETRY_TYPE_TRIANGLE);
  if (geometry == nullptr) embreeFailed("creating a triangle mesh");
  auto* vertexBuffer = static_cast<float*>(rtcSetNewGeometryBuffer(
      geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), vertices.size()));
  if (vertexBuffer == nullptr) {
    rtcReleaseGeometry(geometry);
    embreeFailed("allocating a triangle mesh's vertices");
  }
  for (std::size_t v = 0; v < vertices.size(); ++v) {
    for (int axis = 0; axis < 3; ++axis) vertexBuffer[3 * v + axis] = float(vertices[v][axis]);
  }
  auto* indexBuffer = static_cast<unsigned*>(
      rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                              3 * sizeof(unsigned), triangles.size()));
  if (indexBuffer == nullptr) {
    rtcReleaseGeometry(geometry);
    embreeFailed("allocating a triangle mesh's indices");
  }
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    for (int corner = 0; corner < 3; ++corner) indexBuffer[3 * t + corner] = triangles[t][corner];
  }
  rtcCommitGeometry(geometry);
  const unsigned id = rtcAttachGeometry(scene_, geometry);
  rtcReleaseGeometry(geometry);
  checkEmbree("adding a triangle mesh");
  ++geometryCount_;
  primitiveCount_ += triangles.size();
  for (const auto& triangle : triangles) {
    polygons_.push_back({vertices[triangle[0]], vertices[triangle[1]], vertices[triangle[2]]});
  }
  return id;
}

void OccluderScene::commit() {
  rtcCommitScene(scene_);
  checkEmbree("building the occluder scene");
  committed_ = true;
}

void OccluderScene::trace(SegmentBatch& segments) const {
  RADQUAD_REQUIRE(committed_ || empty());
  if (empty()) return;
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
  // Embree reads the valid mask with aligned loads.
  alignas(64) static constexpr int kAllLanes[16] = {-1, -1, -1, -1, -1, -1, -1, -1,
                                                    -1, -1, -1, -1, -1, -1, -1, -1};
  const std::size_t count = segments.size();
  const std::size_t full = count / 16;
  RTCRay16* packets = embreePackets(segments);
  for (std::size_t p = 0; p < full; ++p) rtcOccluded16(kAllLanes, scene_, &context, &packets[p]);
  if (count % 16 != 0) {
    alignas(64) int valid[16];
    for (std::size_t lane = 0; lane < 16; ++lane) valid[lane] = lane < count % 16 ? -1 : 0;
    rtcOccluded16(valid, scene_, &context, &packets[full]);
  }
}

std::uint64_t OccluderScene::traceMasking(SegmentBatch& segments, double* values) const {
  trace(segments);
  // Embree sets tfar to -inf in the lanes it finds blocked. Eight segments at a time: the far
  // ends widened to double select the values, and the comparison masks (-1 per blocked
  // segment) are summed; the last size % 8 one by one (there are only `size` values).
  using Doubles8 = simd::Doubles8;
  using Counts8 = simd::Int64s8;
  const std::size_t count = segments.size();
  const SegmentPacket* packets = segments.packets();
  Counts8 negativeBlocked = {};
  double* __restrict kept = values;
  const std::size_t grouped = count - count % 8;
  for (std::size_t k = 0; k < grouped; k += 8) {
    simd::Floats8 farFloat;
    std::memcpy(&farFloat, packets[k / 16].tfar + k % 16, sizeof farFloat);
    const Doubles8 far = __builtin_convertvector(farFloat, Doubles8);
    Doubles8 lanes;
    std::memcpy(&lanes, kept + k, sizeof lanes);
    const Counts8 blockedLanes = ~(far >= Doubles8{});  // as !(far >= 0), NaN blocked too
    lanes = blockedLanes ? Doubles8{} : lanes;
    std::memcpy(kept + k, &lanes, sizeof lanes);
    negativeBlocked += blockedLanes;
  }
  std::int64_t blocked = 0;
  for (int lane = 0; lane < 8; ++lane) blocked -= negativeBlocked[lane];
  for (std::size_t k = grouped; k < count; ++k) {
    const bool visible = segments.visible(k);
    kept[k] = visible ? kept[k] : 0.0;
    blocked += visible ? 0 : 1;
  }
  return std::uint64_t(blocked);
}

std::uint64_t OccluderScene::traceMasking(SegmentBatch& segments, const std::uint32_t* owner,
                                          double* values) const {
  trace(segments);
  std::uint64_t blocked = 0;
  for (std::size_t r = 0; r < segments.size(); ++r) {
    if (!segments.visible(r)) {
      values[owner[r]] = 0.0;
      ++blocked;
    }
  }
  return blocked;
}

void OccluderScene::testSegments(const SegmentBatch& segments, std::uint8_t* visible) const {
  SegmentBatch traced = segments;
  trace(traced);
  for (std::size_t k = 0; k < traced.size(); ++k) visible[k] = traced.visible(k) ? 1 : 0;
}

int OccluderScene::closestHit(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction,
                              double& t) const {
  RADQUAD_REQUIRE(committed_ || empty());
  if (empty()) return -1;
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRayHit hit;
  hit.ray.org_x = float(origin.x());
  hit.ray.org_y = float(origin.y());
  hit.ray.org_z = float(origin.z());
  hit.ray.dir_x = float(direction.x());
  hit.ray.dir_y = float(direction.y());
  hit.ray.dir_z = float(direction.z());
  hit.ray.tnear = 0.0f;
  hit.ray.tfar = std::numeric_limits<float>::infinity();
  hit.ray.time = 0.0f;
  hit.ray.mask = 0xFFFFFFFFu;
  hit.ray.id = 0;
  hit.ray.flags = 0;
  hit.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  hit.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(scene_, &context, &hit);
  if (hit.hit.geomID == RTC_INVALID_GEOMETRY_ID) return -1;
  t = hit.ray.tfar;
  return int(hit.hit.geomID);
}

bool OccluderScene::segmentVisible(const Eigen::Vector3d& from, const Eigen::Vector3d& to) const {
  // One packet per thread, reused: the solver asks this of millions of links (which element
  // of a partial link to split), and a fresh batch per call cost an aligned allocation and
  // its page faults each time.
  thread_local SegmentBatch batch;
  batch.clear();
  batch.push(from, to - from);
  trace(batch);
  return batch.visible(0);
}

}  // namespace radquad
