#include "kernel/link_geometry.h"

namespace radquad {

void LinkGeometry::addTriangle(const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                               const Eigen::Vector3d& c) {
  const std::uint32_t first = std::uint32_t(vertices.size());
  vertices.insert(vertices.end(), {a, b, c});
  triangles.push_back({first, first + 1, first + 2});
}

std::unique_ptr<OccluderScene> LinkGeometry::occluderScene() const {
  if (!hasOccluders()) return nullptr;
  auto scene = std::make_unique<OccluderScene>();
  for (const Patch& parallelogram : parallelograms) scene->addParallelogram(parallelogram);
  if (!triangles.empty()) scene->addTriangleMesh(vertices, triangles);
  scene->commit();
  return scene;
}

BuiltLink LinkGeometry::build() const {
  BuiltLink built;
  built.scene = occluderScene();
  built.link = Link{receiver, source, built.scene.get()};
  return built;
}

}  // namespace radquad
