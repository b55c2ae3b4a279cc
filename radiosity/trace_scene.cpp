#include "radiosity/trace_scene.h"

#include <limits>
#include <stdexcept>
#include <type_traits>

#include "kernel/embree_device.h"  // embreeDevice(), checkEmbree(), newParallelogramGeometry()

namespace radquad {
namespace {

// An intersection context carrying the geometry ids to ignore. The filter receives a pointer
// to `base`, the first member of a standard-layout struct, so it may cast back.
struct ExclusionContext {
  RTCIntersectContext base;
  unsigned ignoreA;
  unsigned ignoreB;
};
static_assert(std::is_standard_layout_v<ExclusionContext>);

void rejectIgnored(const RTCFilterFunctionNArguments* args) {
  const auto* context = reinterpret_cast<const ExclusionContext*>(args->context);
  for (unsigned i = 0; i < args->N; ++i) {
    if (args->valid[i] != -1) continue;
    const unsigned geometry = RTCHitN_geomID(args->hit, args->N, i);
    if (geometry == context->ignoreA || geometry == context->ignoreB) args->valid[i] = 0;
  }
}

ExclusionContext exclusionContext(int ignoreA, int ignoreB) {
  ExclusionContext context;
  rtcInitIntersectContext(&context.base);
  context.base.filter = rejectIgnored;
  context.ignoreA = ignoreA < 0 ? RTC_INVALID_GEOMETRY_ID : unsigned(ignoreA);
  context.ignoreB = ignoreB < 0 ? RTC_INVALID_GEOMETRY_ID : unsigned(ignoreB);
  return context;
}

void setRay(RTCRay& ray, const Eigen::Vector3d& origin, const Eigen::Vector3d& direction,
            float far) {
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

}  // namespace

TraceScene::TraceScene(const Scene& scene) {
  RTCDevice device = embreeDevice();
  if (!rtcGetDeviceProperty(device, RTC_DEVICE_PROPERTY_FILTER_FUNCTION_SUPPORTED)) {
    throw std::runtime_error("the Embree library was built without filter functions");
  }
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

int TraceScene::firstHit(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction,
                         int ignore, double& t) const {
  ExclusionContext context = exclusionContext(ignore, ignore);
  RTCRayHit hit;
  setRay(hit.ray, origin, direction, std::numeric_limits<float>::infinity());
  hit.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  hit.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(scene_, &context.base, &hit);
  if (hit.hit.geomID == RTC_INVALID_GEOMETRY_ID) return -1;
  t = hit.ray.tfar;
  return int(hit.hit.geomID);
}

bool TraceScene::unobstructed(const Eigen::Vector3d& from, const Eigen::Vector3d& to,
                              int ignoreA, int ignoreB) const {
  ExclusionContext context = exclusionContext(ignoreA, ignoreB);
  RTCRay ray;
  setRay(ray, from, to - from, 1.0f);
  rtcOccluded1(scene_, &context.base, &ray);
  return ray.tfar >= 0.0f;  // Embree sets tfar to -inf when the segment is blocked
}

}  // namespace radquad
