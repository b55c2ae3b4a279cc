#include "kernel/patch.h"

#include <cmath>
#include <sstream>

#include "kernel/input_error.h"

namespace radquad {
namespace {

bool allFinite(const Eigen::Vector3d& v) {
  return v.allFinite();
}

std::string formatVector(const Eigen::Vector3d& v) {
  std::ostringstream out;
  out.precision(17);
  out << "[" << v.x() << ", " << v.y() << ", " << v.z() << "]";
  return out.str();
}

}  // namespace

Patch Patch::make(const Eigen::Vector3d& origin, const Eigen::Vector3d& edgeU,
                  const Eigen::Vector3d& edgeV, const std::string& what) {
  if (!allFinite(origin) || !allFinite(edgeU) || !allFinite(edgeV)) {
    throw InputError(what + ": every coordinate must be a finite number");
  }
  // Visibility is traced in single precision (Embree): corners beyond kMaxCoordinate would
  // overflow there (float's range ends at 3.4e38, and ray lengths are squared).
  for (const Eigen::Vector3d& corner :
       {origin, Eigen::Vector3d(origin + edgeU), Eigen::Vector3d(origin + edgeV),
        Eigen::Vector3d(origin + edgeU + edgeV)}) {
    if (!(corner.cwiseAbs().maxCoeff() <= kMaxCoordinate)) {
      throw InputError(what + ": a corner lies beyond the coordinate limit of 1e15 (" +
                       formatVector(corner) + ")");
    }
  }
  const Eigen::Vector3d cross = edgeU.cross(edgeV);
  const double area = cross.norm();
  const double edgeProduct = edgeU.norm() * edgeV.norm();
  // A relative test: the sine of the angle between the edges must not vanish.
  if (!(area > 0.0) || !std::isfinite(area) || area <= 1e-9 * edgeProduct) {
    throw InputError(what + ": degenerate patch (zero area: edge_u " + formatVector(edgeU) +
                     " and edge_v " + formatVector(edgeV) + " are zero or parallel)");
  }
  Patch patch;
  patch.origin = origin;
  patch.edgeU = edgeU;
  patch.edgeV = edgeV;
  patch.normal = cross / area;
  patch.area = area;
  return patch;
}

Eigen::Vector2d Patch::parametersOf(const Eigen::Vector3d& point) const {
  const Eigen::Vector3d r = point - origin;
  const double aa = edgeU.squaredNorm(), ab = edgeU.dot(edgeV), bb = edgeV.squaredNorm();
  const double ar = edgeU.dot(r), br = edgeV.dot(r);
  const double determinant = aa * bb - ab * ab;
  return {(bb * ar - ab * br) / determinant, (aa * br - ab * ar) / determinant};
}

std::string Patch::toString() const {
  return "Patch{origin " + formatVector(origin) + ", edge_u " + formatVector(edgeU) + ", edge_v " +
         formatVector(edgeV) + "}";
}

}  // namespace radquad
