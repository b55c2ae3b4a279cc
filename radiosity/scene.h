// A radiosity scene: one-sided parallelogram patches with a diffuse reflectance and an
// emitted radiosity per colour channel, and an optional pinhole camera for rendering.
// Every patch occludes every link it does not belong to.
//
// The JSON form (parsed in experiments/, see radiosity/README.md):
//   {"patches": [PATCH...], "camera": CAMERA}
//   PATCH  = {"origin", "edge_u", "edge_v", "reflectance": [r,g,b],
//             "emission": [r,g,b] (default 0), "name" (optional)}
//   CAMERA = {"eye", "look_at", "up", "fov_degrees", "width", "height"}
#pragma once

#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

#include "kernel/patch.h"

namespace radquad {

struct ScenePatch {
  std::string name;
  Patch patch;
  Eigen::Vector3d reflectance = Eigen::Vector3d::Zero();  // rho per channel, in [0, 1)
  Eigen::Vector3d emission = Eigen::Vector3d::Zero();     // emitted radiosity B^e, >= 0
};

struct Camera {
  Eigen::Vector3d eye = Eigen::Vector3d::Zero();
  Eigen::Vector3d lookAt = Eigen::Vector3d::UnitZ();
  Eigen::Vector3d up = Eigen::Vector3d::UnitY();
  double fovDegrees = 40.0;  // vertical field of view
  int width = 512;
  int height = 512;
};

struct Scene {
  std::vector<ScenePatch> patches;
  std::optional<Camera> camera;
};

// Throws InputError naming the patch ("<where>: patches[k] (name)") when a reflectance is
// outside [0, 1) or an emission is negative, when the scene has no patch, or when a camera
// is degenerate. `where` names the scene (a path or a built-in name).
void validateScene(const Scene& scene, const std::string& where);

// "patches[k]" or "patches[k] (name)".
std::string describePatch(const Scene& scene, std::size_t index);

// A view of the whole scene for scenes without a camera: from outside its bounding box,
// looking at its centre.
Camera defaultCamera(const Scene& scene);

// The built-in scenes by name: "cornell" and "slats"; nullopt for any other name.
std::optional<Scene> builtinScene(const std::string& name);
std::vector<std::string> builtinSceneNames();

}  // namespace radquad
