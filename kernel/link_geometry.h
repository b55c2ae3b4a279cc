// A link as data: its receiver and source patches and the occluders that may lie between
// them, parallelograms and triangles. Link files (experiments/json_input.h), the study's
// generator (experiments/scenarios/scenario.h), the scene-derived links
// (experiments/study/scene_links.h), the benchmarks and the tests describe links with it;
// build() gives the committed occluder scene and the Link the kernel integrates.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <memory>
#include <vector>

#include "kernel/coupling.h"
#include "kernel/occluder_scene.h"
#include "kernel/patch.h"

namespace radquad {

// A Link together with the occluder scene it points into.
struct BuiltLink {
  std::unique_ptr<OccluderScene> scene;  // null when nothing is in the way
  Link link;
};

struct LinkGeometry {
  Patch receiver;
  Patch source;
  std::vector<Patch> parallelograms;
  std::vector<Eigen::Vector3d> vertices;                // of the triangles
  std::vector<std::array<std::uint32_t, 3>> triangles;  // indices into vertices

  bool hasOccluders() const { return !parallelograms.empty() || !triangles.empty(); }
  // Appends a triangle with its own three vertices.
  void addTriangle(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c);
  // The committed occluder scene (the parallelograms, then the triangles as one mesh); null
  // when there is nothing in the way.
  std::unique_ptr<OccluderScene> occluderScene() const;
  BuiltLink build() const;
};

}  // namespace radquad
