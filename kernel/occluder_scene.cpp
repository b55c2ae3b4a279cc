#include "kernel/occluder_scene.h"

#include "kernel/input_error.h"

#include <algorithm>
#include <cstdio>
#include <limits>
#include <mutex>
#include <stdexcept>
#include <string>

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
    RTCRay16 fresh;
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
  RTCRay16* packets = segments.packets();
  for (std::size_t p = 0; p < full; ++p) rtcOccluded16(kAllLanes, scene_, &context, &packets[p]);
  if (count % 16 != 0) {
    alignas(64) int valid[16];
    for (std::size_t lane = 0; lane < 16; ++lane) valid[lane] = lane < count % 16 ? -1 : 0;
    rtcOccluded16(valid, scene_, &context, &packets[full]);
  }
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
  SegmentBatch batch;
  batch.push(from, to - from);
  std::uint8_t visible = 0;
  testSegments(batch, &visible);
  return visible != 0;
}

}  // namespace radquad
