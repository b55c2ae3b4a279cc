#include "radiosity/render.h"

#include <stb_image_write.h>
#include <tbb/parallel_for.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <stdexcept>

#include "kernel/occluder_scene.h"

namespace radquad {
namespace {

// An Embree scene of all patches; geometry id = patch index (ids count from 0 in add order).
std::unique_ptr<OccluderScene> primaryScene(const Scene& scene) {
  auto primary = std::make_unique<OccluderScene>();
  for (const ScenePatch& patch : scene.patches) primary->addParallelogram(patch.patch);
  primary->commit();
  return primary;
}

// (u, v) of a point of the patch's plane: the least-squares solution of
// u edgeU + v edgeV = point - origin, clamped to the unit square.
void patchCoordinates(const Patch& patch, const Eigen::Vector3d& point, double& u, double& v) {
  const Eigen::Vector2d uv = patch.parametersOf(point);
  u = std::clamp(uv.x(), 0.0, 1.0);
  v = std::clamp(uv.y(), 0.0, 1.0);
}

void appendBytes(void* context, void* data, int size) {
  static_cast<std::string*>(context)->append(static_cast<const char*>(data), std::size_t(size));
}

}  // namespace

RadianceImage renderRadiosity(const Hierarchy& hierarchy, const Camera& camera) {
  const Scene& scene = hierarchy.scene();
  const std::unique_ptr<OccluderScene> primary = primaryScene(scene);
  RadianceImage image;
  image.width = camera.width;
  image.height = camera.height;
  image.rgb.assign(std::size_t(camera.width) * std::size_t(camera.height) * 3, 0.0f);
  const Eigen::Vector3d forward = (camera.lookAt - camera.eye).normalized();
  const Eigen::Vector3d right = forward.cross(camera.up).normalized();
  const Eigen::Vector3d up = right.cross(forward);
  const double tanHalf = std::tan(0.5 * camera.fovDegrees * M_PI / 180.0);
  const double aspect = double(camera.width) / double(camera.height);
  tbb::parallel_for(0, camera.height, [&](int y) {
    for (int x = 0; x < camera.width; ++x) {
      const double px = (2.0 * (x + 0.5) / camera.width - 1.0) * aspect * tanHalf;
      const double py = (1.0 - 2.0 * (y + 0.5) / camera.height) * tanHalf;
      const Eigen::Vector3d direction = (forward + px * right + py * up).normalized();
      double distance = 0.0;
      const int p = primary->closestHit(camera.eye, direction, distance);
      if (p < 0) continue;
      const Patch& patch = scene.patches[std::size_t(p)].patch;
      if (patch.normal.dot(direction) >= 0.0) continue;  // the back of a one-sided patch
      double u = 0.0, v = 0.0;
      patchCoordinates(patch, camera.eye + distance * direction, u, v);
      const Eigen::Vector3d radiosity = hierarchy.radiosityAt(p, u, v);
      float* pixel = image.rgb.data() + 3 * (std::size_t(y) * std::size_t(camera.width) + x);
      for (int c = 0; c < 3; ++c) pixel[c] = float(std::max(0.0, radiosity[c]));
    }
  });
  return image;
}

double automaticExposure(const RadianceImage& image) {
  const std::size_t pixels = std::size_t(image.width) * std::size_t(image.height);
  if (pixels == 0) return 1.0;
  std::vector<float> brightest(pixels);
  for (std::size_t k = 0; k < pixels; ++k) {
    brightest[k] = std::max({image.rgb[3 * k], image.rgb[3 * k + 1], image.rgb[3 * k + 2]});
  }
  const std::size_t rank = std::min(pixels - 1, std::size_t(0.97 * double(pixels)));
  std::nth_element(brightest.begin(), brightest.begin() + std::ptrdiff_t(rank), brightest.end());
  return brightest[rank] > 0.0f ? 1.0 / brightest[rank] : 1.0;
}

std::string encodePng(const RadianceImage& image, double exposure, double gamma) {
  const std::size_t pixels = std::size_t(image.width) * std::size_t(image.height);
  if (exposure <= 0.0) exposure = automaticExposure(image);
  std::vector<unsigned char> bytes(pixels * 3);
  for (std::size_t k = 0; k < pixels * 3; ++k) {
    const double value = std::clamp(double(image.rgb[k]) * exposure, 0.0, 1.0);
    bytes[k] = static_cast<unsigned char>(std::lround(255.0 * std::pow(value, 1.0 / gamma)));
  }
  std::string png;
  if (!stbi_write_png_to_func(appendBytes, &png, image.width, image.height, 3, bytes.data(),
                              image.width * 3)) {
    throw std::runtime_error("PNG encoding failed");
  }
  return png;
}

}  // namespace radquad
