#include "radiosity/scene.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <vector>

#include "kernel/input_error.h"
#include "kernel/patch_intersection.h"

namespace radquad {

std::string describePatch(const Scene& scene, std::size_t index) {
  std::string text = "patches[" + std::to_string(index) + "]";
  if (index < scene.patches.size() && !scene.patches[index].name.empty()) {
    text += " (" + scene.patches[index].name + ")";
  }
  return text;
}

namespace {

// Two patches facing the same way that overlap in their common plane would both receive the
// light that reaches that place and both reflect it (the solver links neither with the other,
// a path tracer's ray meets one of them): the scene is refused, naming both. Patches in one
// plane facing the same way are grouped (unit normal and offset rounded to 1e-9 of the
// scene's size), and each group is swept along one in-plane axis, so only patches whose
// extents overlap there are compared (touching neighbours are legal and pass).
void refuseOverlaps(const Scene& scene, const std::string& where) {
  const std::size_t count = scene.patches.size();
  if (count < 2) return;
  Eigen::Vector3d low = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector3d high = -low;
  for (const ScenePatch& item : scene.patches) {
    for (const Eigen::Vector3d& corner : item.patch.corners()) {
      low = low.cwiseMin(corner);
      high = high.cwiseMax(corner);
    }
  }
  const double size = std::max((high - low).norm(), std::numeric_limits<double>::min());
  const double step = 1e-9;
  struct Entry {
    std::array<long long, 4> plane;
    double from, to;      // the patch's extent along its group's first in-plane axis
    double across, till;  // and along the second
    std::size_t index;
  };
  std::vector<Entry> entries(count);
  for (std::size_t k = 0; k < count; ++k) {
    const Patch& patch = scene.patches[k].patch;
    const Eigen::Vector3d n = patch.normal.normalized();
    const double offset = n.dot(patch.origin) / size;
    entries[k].plane = {std::llround(n.x() / step), std::llround(n.y() / step),
                        std::llround(n.z() / step), std::llround(offset / step)};
    entries[k].index = k;
  }
  std::sort(entries.begin(), entries.end(), [](const Entry& a, const Entry& b) {
    return a.plane < b.plane || (a.plane == b.plane && a.index < b.index);
  });
  for (std::size_t first = 0; first < count;) {
    std::size_t last = first + 1;
    while (last < count && entries[last].plane == entries[first].plane) ++last;
    if (last - first > 1) {
      // An in-plane axis of the group, and each patch's extent along it.
      const Eigen::Vector3d n = scene.patches[entries[first].index].patch.normal.normalized();
      const Eigen::Vector3d axis =
          (std::abs(n.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY())
              .cross(n)
              .normalized();
      const Eigen::Vector3d other = n.cross(axis);
      for (std::size_t k = first; k < last; ++k) {
        Entry& entry = entries[k];
        entry.from = entry.across = std::numeric_limits<double>::infinity();
        entry.to = entry.till = -entry.from;
        for (const Eigen::Vector3d& corner : scene.patches[entry.index].patch.corners()) {
          entry.from = std::min(entry.from, axis.dot(corner));
          entry.to = std::max(entry.to, axis.dot(corner));
          entry.across = std::min(entry.across, other.dot(corner));
          entry.till = std::max(entry.till, other.dot(corner));
        }
      }
      std::sort(entries.begin() + std::ptrdiff_t(first), entries.begin() + std::ptrdiff_t(last),
                [](const Entry& a, const Entry& b) { return a.from < b.from; });
      for (std::size_t a = first; a < last; ++a) {
        for (std::size_t b = a + 1; b < last && entries[b].from < entries[a].to; ++b) {
          // Apart along the second axis (or only touching there): no overlap.
          if (entries[b].across >= entries[a].till || entries[a].across >= entries[b].till) {
            continue;
          }
          const std::size_t i = std::min(entries[a].index, entries[b].index);
          const std::size_t j = std::max(entries[a].index, entries[b].index);
          if (const auto overlap = patchesInterpenetrate(scene.patches[i].patch,
                                                         scene.patches[j].patch)) {
            throw InputError(where + ": " + describePatch(scene, i) + " and " +
                             describePatch(scene, j) + " face the same way and " + *overlap +
                             ": the solver would light both (merge them, or move one)");
          }
        }
      }
    }
    first = last;
  }
}

}  // namespace

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
  refuseOverlaps(scene, where);
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
