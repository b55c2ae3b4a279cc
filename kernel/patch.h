// A planar parallelogram patch (docs/design.md, "Conventions"):
//   x(u,v) = origin + u edgeU + v edgeV,  (u,v) in [0,1]^2,
//   normal n = (edgeU x edgeV) / |edgeU x edgeV|,  area A = |edgeU x edgeV|.
// A patch is one-sided: it emits and receives on the side its normal points to.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <string>

namespace radquad {

// The largest coordinate magnitude of a patch's corners (scene units): visibility is traced in
// single precision.
inline constexpr double kMaxCoordinate = 1e15;

struct Patch {
  Eigen::Vector3d origin;
  Eigen::Vector3d edgeU;
  Eigen::Vector3d edgeV;
  Eigen::Vector3d normal;
  double area = 0.0;

  // Builds a validated patch. `what` names the patch in error messages
  // (for example "source" or "occluders[3]"). Throws InputError when a coordinate is not
  // finite, a corner lies beyond kMaxCoordinate, or the parallelogram is degenerate (zero
  // area, or edges parallel to within 1e-9).
  static Patch make(const Eigen::Vector3d& origin, const Eigen::Vector3d& edgeU,
                    const Eigen::Vector3d& edgeV, const std::string& what);

  Eigen::Vector3d pointAt(double u, double v) const { return origin + u * edgeU + v * edgeV; }
  Eigen::Vector3d centre() const { return pointAt(0.5, 0.5); }
  // The corners o, o + a, o + a + b, o + b: counter-clockwise about the normal.
  std::array<Eigen::Vector3d, 4> corners() const {
    return {origin, origin + edgeU, origin + edgeU + edgeV, origin + edgeV};
  }
  // (u, v) of the point's projection onto the patch's plane: the least-squares solution of
  // u edgeU + v edgeV = point - origin (outside [0, 1]^2 beyond the edges).
  Eigen::Vector2d parametersOf(const Eigen::Vector3d& point) const;

  std::string toString() const;
};

}  // namespace radquad
