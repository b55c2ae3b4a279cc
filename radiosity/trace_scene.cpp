#include "radiosity/trace_scene.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <type_traits>

#include "kernel/embree_device.h"  // embreeDevice(), checkEmbree(), newParallelogramGeometry()

namespace radquad {
namespace {

using Vec = Eigen::Vector3d;

// An intersection context carrying the geometry ids to ignore: two sorted lists (plane
// mates). The filter receives a pointer to `base`, the first member of a standard-layout
// struct, so it may cast back.
struct ExclusionContext {
  RTCIntersectContext base;
  const int* ignoreA;
  std::size_t countA;
  const int* ignoreB;
  std::size_t countB;
};
static_assert(std::is_standard_layout_v<ExclusionContext>);

bool listed(const int* ids, std::size_t count, int id) {
  for (std::size_t k = 0; k < count; ++k) {
    if (ids[k] == id) return true;
  }
  return false;
}

void rejectIgnored(const RTCFilterFunctionNArguments* args) {
  const auto* context = reinterpret_cast<const ExclusionContext*>(args->context);
  for (unsigned i = 0; i < args->N; ++i) {
    if (args->valid[i] != -1) continue;
    const int geometry = int(RTCHitN_geomID(args->hit, args->N, i));
    if (listed(context->ignoreA, context->countA, geometry) ||
        listed(context->ignoreB, context->countB, geometry)) {
      args->valid[i] = 0;
    }
  }
}

ExclusionContext exclusionContext(const std::vector<int>* a, const std::vector<int>* b) {
  ExclusionContext context;
  rtcInitIntersectContext(&context.base);
  context.base.filter = rejectIgnored;
  context.ignoreA = a ? a->data() : nullptr;
  context.countA = a ? a->size() : 0;
  context.ignoreB = b ? b->data() : nullptr;
  context.countB = b ? b->size() : 0;
  return context;
}

void setRay(RTCRay& ray, const Vec& origin, const Vec& direction, float far) {
  ray.org_x = float(origin.x());
  ray.org_y = float(origin.y());
  ray.org_z = float(origin.z());
  ray.dir_x = float(direction.x());
  ray.dir_y = float(direction.y());
  ray.dir_z = float(direction.z());
  ray.tnear = 0.0f;
  ray.tfar = far;
  ray.time = 0.0f;
  ray.mask = 0xFFFFFFFFu;
  ray.id = 0;
  ray.flags = 0;
}

// kPlaneMateTolerance times the largest coordinate magnitude of the scene's corners.
double mateTolerance(const Scene& scene) {
  double largest = 0.0;
  for (const ScenePatch& item : scene.patches) {
    for (const Vec& corner : item.patch.corners())
      largest = std::max(largest, corner.cwiseAbs().maxCoeff());
  }
  return kPlaneMateTolerance * std::max(largest, std::numeric_limits<double>::min());
}

// Every corner of `other` within `tolerance` of `patch`'s plane.
bool inPlaneOf(const Patch& patch, const Patch& other, double tolerance) {
  for (const Vec& corner : other.corners()) {
    if (!(std::abs(patch.normal.dot(corner - patch.origin)) <= tolerance)) return false;
  }
  return true;
}

// Whether the projection of `point` onto the patch's plane lies in the patch, its edges
// grown by `tolerance`.
bool coversPoint(const Patch& patch, const Vec& point, double tolerance) {
  const Eigen::Vector2d uv = patch.parametersOf(point);
  const double du = tolerance / patch.edgeU.norm(), dv = tolerance / patch.edgeV.norm();
  return uv.x() >= -du && uv.x() <= 1.0 + du && uv.y() >= -dv && uv.y() <= 1.0 + dv;
}

}  // namespace

std::vector<std::vector<int>> planeMates(const Scene& scene) {
  const std::size_t count = scene.patches.size();
  const double tolerance = mateTolerance(scene);
  std::vector<Vec> low(count), high(count);
  for (std::size_t k = 0; k < count; ++k) {
    low[k] = Vec::Constant(std::numeric_limits<double>::infinity());
    high[k] = -low[k];
    for (const Vec& corner : scene.patches[k].patch.corners()) {
      low[k] = low[k].cwiseMin(corner);
      high[k] = high[k].cwiseMax(corner);
    }
    low[k].array() -= tolerance;
    high[k].array() += tolerance;
  }
  // A sweep along x: only boxes that overlap there are compared.
  std::vector<int> order(count);
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](int a, int b) {
    return low[a].x() < low[b].x() || (low[a].x() == low[b].x() && a < b);
  });
  std::vector<std::vector<int>> mates(count);
  for (std::size_t k = 0; k < count; ++k) mates[k].push_back(int(k));
  for (std::size_t i = 0; i < count; ++i) {
    const int a = order[i];
    for (std::size_t j = i + 1; j < count && low[order[j]].x() <= high[a].x(); ++j) {
      const int b = order[j];
      if ((low[b].array() > high[a].array()).any() || (low[a].array() > high[b].array()).any()) {
        continue;
      }
      const Patch& pa = scene.patches[std::size_t(a)].patch;
      const Patch& pb = scene.patches[std::size_t(b)].patch;
      if (inPlaneOf(pa, pb, tolerance) && inPlaneOf(pb, pa, tolerance)) {
        mates[std::size_t(a)].push_back(b);
        mates[std::size_t(b)].push_back(a);
      }
    }
  }
  for (std::vector<int>& list : mates) std::sort(list.begin(), list.end());
  return mates;
}

TraceScene::TraceScene(const Scene& scene)
    : mates_(planeMates(scene)), tolerance_(mateTolerance(scene)) {
  RTCDevice device = embreeDevice();
  if (!rtcGetDeviceProperty(device, RTC_DEVICE_PROPERTY_FILTER_FUNCTION_SUPPORTED)) {
    throw std::runtime_error("the Embree library was built without filter functions");
  }
  for (const ScenePatch& item : scene.patches) patches_.push_back(item.patch);
  scene_ = rtcNewScene(device);
  // Robust traversal: a ray through an edge shared by two patches (or a quad's diagonal)
  // must not slip between them.
  rtcSetSceneFlags(scene_, RTC_SCENE_FLAG_ROBUST | RTC_SCENE_FLAG_CONTEXT_FILTER_FUNCTION);
  rtcSetSceneBuildQuality(scene_, RTC_BUILD_QUALITY_HIGH);
  try {
    for (std::size_t k = 0; k < scene.patches.size(); ++k) {
      const Patch& patch = scene.patches[k].patch;
      RTCGeometry geometry = newParallelogramGeometry(device, patch);
      rtcAttachGeometryByID(scene_, geometry, unsigned(k));
      rtcReleaseGeometry(geometry);
      checkEmbree("adding a patch to the traced scene");
    }
    rtcCommitScene(scene_);
    checkEmbree("building the traced scene");
  } catch (...) {
    rtcReleaseScene(scene_);  // the destructor does not run when the constructor throws
    scene_ = nullptr;
    throw;
  }
}

TraceScene::~TraceScene() {
  if (scene_) rtcReleaseScene(scene_);
}

int TraceScene::firstHit(const Vec& origin, const Vec& direction, int from, double& t) const {
  ExclusionContext context =
      exclusionContext(from >= 0 ? &mates_[std::size_t(from)] : nullptr, nullptr);
  RTCRayHit hit;
  setRay(hit.ray, origin, direction, std::numeric_limits<float>::infinity());
  hit.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  hit.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(scene_, &context.base, &hit);
  if (hit.hit.geomID == RTC_INVALID_GEOMETRY_ID) return -1;
  t = hit.ray.tfar;
  const int h = int(hit.hit.geomID);
  const std::vector<int>& candidates = mates_[std::size_t(h)];
  if (candidates.size() == 1 || direction.dot(patches_[std::size_t(h)].normal) < 0.0) return h;
  // A back side: on a two-sided surface, the face turned to the ray.
  const Vec point = origin + t * direction;
  for (const int mate : candidates) {
    const Patch& patch = patches_[std::size_t(mate)];
    if (direction.dot(patch.normal) < 0.0 && coversPoint(patch, point, tolerance_)) return mate;
  }
  return h;
}

bool TraceScene::unobstructed(const Vec& from, const Vec& to, int patchA, int patchB) const {
  ExclusionContext context =
      exclusionContext(&mates_[std::size_t(patchA)], &mates_[std::size_t(patchB)]);
  RTCRay ray;
  setRay(ray, from, to - from, 1.0f);
  rtcOccluded1(scene_, &context.base, &ray);
  return ray.tfar >= 0.0f;  // Embree sets tfar to -inf when the segment is blocked
}

bool TraceScene::mates(int a, int b) const {
  const std::vector<int>& list = mates_[std::size_t(a)];
  return std::binary_search(list.begin(), list.end(), b);
}

}  // namespace radquad
