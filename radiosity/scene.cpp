#include "radiosity/scene.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>

#include "kernel/input_error.h"

namespace radquad {

std::string describePatch(const Scene& scene, std::size_t index) {
  std::string text = "patches[" + std::to_string(index) + "]";
  if (index < scene.patches.size() && !scene.patches[index].name.empty()) {
    text += " (" + scene.patches[index].name + ")";
  }
  return text;
}

void validateScene(const Scene& scene, const std::string& where) {
  if (scene.patches.empty()) throw InputError(where + ": the scene has no patches");
  static const char* kChannels[3] = {"red", "green", "blue"};
  for (std::size_t k = 0; k < scene.patches.size(); ++k) {
    const ScenePatch& patch = scene.patches[k];
    for (int c = 0; c < 3; ++c) {
      const double rho = patch.reflectance[c];
      // rho = 1 in a closed scene makes the radiosity equation singular (no absorption).
      if (!(rho >= 0.0 && rho < 1.0)) {
        throw InputError(where + ": " + describePatch(scene, k) + ": reflectance (" + kChannels[c] +
                         ") is " + std::to_string(rho) + ", outside [0, 1)");
      }
      const double emission = patch.emission[c];
      if (!(emission >= 0.0) || !std::isfinite(emission)) {
        throw InputError(where + ": " + describePatch(scene, k) + ": emission (" + kChannels[c] +
                         ") is " + std::to_string(emission) + ", must be finite and >= 0");
      }
    }
  }
  if (scene.camera) {
    const Camera& camera = *scene.camera;
    const Eigen::Vector3d view = camera.lookAt - camera.eye;
    if (view.norm() <= 0.0) throw InputError(where + ": camera: eye and look_at coincide");
    if (view.cross(camera.up).norm() <= 1e-9 * view.norm() * camera.up.norm()) {
      throw InputError(where + ": camera: up is zero or parallel to the view direction");
    }
    if (!(camera.fovDegrees > 0.0 && camera.fovDegrees < 180.0)) {
      throw InputError(where + ": camera: fov_degrees must be in (0, 180)");
    }
    if (camera.width < 1 || camera.height < 1 || camera.width > 16384 || camera.height > 16384) {
      throw InputError(where + ": camera: width and height must be in 1..16384");
    }
  }
}

Camera defaultCamera(const Scene& scene) {
  Eigen::Vector3d low = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector3d high = -low;
  for (const ScenePatch& item : scene.patches) {
    const Patch& p = item.patch;
    for (const Eigen::Vector3d& corner : p.corners()) {
      low = low.cwiseMin(corner);
      high = high.cwiseMax(corner);
    }
  }
  Camera camera;
  const Eigen::Vector3d centre = 0.5 * (low + high);
  const double radius = std::max(0.5 * (high - low).norm(), 1e-6);
  camera.lookAt = centre;
  // From the -z side, slightly above, far enough that a 40 degree view holds the bounds.
  const Eigen::Vector3d direction = Eigen::Vector3d(0.3, 0.4, -1.0).normalized();
  camera.eye = centre + direction * (radius / std::sin(0.5 * camera.fovDegrees * M_PI / 180.0));
  camera.up = Eigen::Vector3d::UnitY();
  return camera;
}

}  // namespace radquad
