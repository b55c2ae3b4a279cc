// The built-in scenes.
//   cornell: a closed 5.5-unit Cornell-style box (red left wall, green right wall, white
//            floor, ceiling, back and front walls; the camera at the front wall), a short and a
//            tall block standing on the floor, and an area light just below the ceiling's centre,
//            facing down.
//   slats:   a 6 x 3 x 4 room split by a screen of tilted two-sided slats; a window-like
//            emitter on the left wall lights the right half only through the slats, so
//            most links across the screen are partially occluded.
#include <Eigen/Geometry>
#include <cmath>

#include "radiosity/scene.h"

namespace radquad {
namespace {

using Vec = Eigen::Vector3d;

// A parallelogram whose normal points along `facing` (its edges are swapped if needed).
Patch facingPatch(const Vec& origin, const Vec& edgeU, const Vec& edgeV, const Vec& facing,
                  const std::string& name) {
  if (edgeU.cross(edgeV).dot(facing) >= 0.0) return Patch::make(origin, edgeU, edgeV, name);
  return Patch::make(origin, edgeV, edgeU, name);
}

void addPatch(Scene& scene, const std::string& name, const Patch& patch, const Vec& reflectance,
              const Vec& emission = Vec::Zero()) {
  scene.patches.push_back(ScenePatch{name, patch, reflectance, emission});
}

// An axis-aligned room [0,size.x] x [0,size.y] x [0,size.z] with inward normals.
void addRoom(Scene& scene, const Vec& size, const Vec& left, const Vec& right, const Vec& white) {
  const Vec x = Vec::UnitX() * size.x(), y = Vec::UnitY() * size.y(), z = Vec::UnitZ() * size.z();
  addPatch(scene, "floor", facingPatch(Vec::Zero(), x, z, Vec::UnitY(), "floor"), white);
  addPatch(scene, "ceiling", facingPatch(y, x, z, -Vec::UnitY(), "ceiling"), white);
  addPatch(scene, "front wall", facingPatch(z, x, y, -Vec::UnitZ(), "front wall"), white);
  addPatch(scene, "back wall", facingPatch(Vec::Zero(), x, y, Vec::UnitZ(), "back wall"), white);
  addPatch(scene, "left wall", facingPatch(Vec::Zero(), z, y, Vec::UnitX(), "left wall"), left);
  addPatch(scene, "right wall", facingPatch(x, z, y, -Vec::UnitX(), "right wall"), right);
}

// A box standing on the floor: four sides and a top with outward normals, rotated by `angle`
// (radians) about the vertical through its centre (cx, cz).
void addBlock(Scene& scene, const std::string& name, double cx, double cz, double width,
              double depth, double height, double angle, const Vec& reflectance) {
  const Vec ex = Vec(std::cos(angle), 0.0, std::sin(angle)) * width;
  const Vec ez = Vec(-std::sin(angle), 0.0, std::cos(angle)) * depth;
  const Vec ey = Vec::UnitY() * height;
  const Vec base = Vec(cx, 0.0, cz) - 0.5 * ex - 0.5 * ez;
  addPatch(scene, name + " -u", facingPatch(base, ez, ey, -ex, name), reflectance);
  addPatch(scene, name + " +u", facingPatch(base + ex, ez, ey, ex, name), reflectance);
  addPatch(scene, name + " -v", facingPatch(base, ex, ey, -ez, name), reflectance);
  addPatch(scene, name + " +v", facingPatch(base + ez, ex, ey, ez, name), reflectance);
  addPatch(scene, name + " top", facingPatch(base + ey, ex, ez, Vec::UnitY(), name), reflectance);
}

Scene cornellScene() {
  Scene scene;
  const double size = 5.5;
  const Vec white(0.725, 0.71, 0.68), red(0.63, 0.065, 0.05), green(0.14, 0.45, 0.091);
  addRoom(scene, Vec::Constant(size), red, green, white);
  addBlock(scene, "short block", 3.75, 2.6, 1.65, 1.65, 1.65, -0.29, white);
  addBlock(scene, "tall block", 1.85, 1.7, 1.65, 1.65, 3.3, 0.29, white);
  // The light hangs 1e-3 of the box below the ceiling, so the ceiling never touches it.
  const double lightY = size * (1.0 - 1e-3);
  const Vec lightOrigin(0.5 * size - 0.65, lightY, 0.5 * size - 0.525);
  addPatch(scene, "light",
           facingPatch(lightOrigin, Vec(1.3, 0, 0), Vec(0, 0, 1.05), -Vec::UnitY(), "light"),
           Vec::Constant(0.78), Vec(40.0, 32.0, 24.0));
  Camera camera;
  camera.eye = Vec(0.5 * size, 0.5 * size, size - 0.05);
  camera.lookAt = Vec(0.5 * size, 0.5 * size, 0.0);
  camera.up = Vec::UnitY();
  camera.fovDegrees = 75.0;
  scene.camera = camera;
  return scene;
}

Scene slatsScene() {
  Scene scene;
  const Vec size(6.0, 3.0, 4.0);
  const Vec white = Vec::Constant(0.7), warm(0.75, 0.6, 0.45), cool(0.45, 0.55, 0.75);
  addRoom(scene, size, warm, cool, white);
  // The emitter: a 1.6 x 1.6 window on the left wall, 1e-3 in front of it.
  addPatch(
      scene, "window",
      facingPatch(Vec(0.003, 0.9, 1.2), Vec(0, 0, 1.6), Vec(0, 1.6, 0), Vec::UnitX(), "window"),
      Vec::Zero(), Vec::Constant(20.0));
  // The screen at x = 2.2: slats tilted 40 degrees from horizontal, each two-sided (two patches
  // 0.01 apart, facing away from each other).
  const int slatCount = 10;
  const double width = 0.28, tilt = 40.0 * M_PI / 180.0, thickness = 0.01;
  const Vec across = Vec(std::cos(tilt), std::sin(tilt), 0.0) * width;
  const Vec along = Vec(0.0, 0.0, 3.6);
  const Vec normal = across.cross(along).normalized();
  for (int k = 0; k < slatCount; ++k) {
    const Vec centre(2.2, 0.35 + 0.25 * k, 2.0);
    const Vec origin = centre - 0.5 * across - 0.5 * along;
    const std::string name = "slat " + std::to_string(k);
    addPatch(scene, name + " a",
             facingPatch(origin + 0.5 * thickness * normal, across, along, normal, name), white);
    addPatch(scene, name + " b",
             facingPatch(origin - 0.5 * thickness * normal, across, along, -normal, name), white);
  }
  Camera camera;
  camera.eye = Vec(5.85, 1.6, 2.0);
  camera.lookAt = Vec(0.0, 1.4, 2.0);
  camera.up = Vec::UnitY();
  camera.fovDegrees = 70.0;
  scene.camera = camera;
  return scene;
}

}  // namespace

std::vector<std::string> builtinSceneNames() {
  return {"cornell", "slats"};
}

std::optional<Scene> builtinScene(const std::string& name) {
  if (name == "cornell") return cornellScene();
  if (name == "slats") return slatsScene();
  return std::nullopt;
}

}  // namespace radquad
