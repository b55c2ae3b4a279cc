// Helpers shared by the product and the scattered coupling paths (kernel/coupling.cpp,
// kernel/scattered_coupling.cpp); not part of the kernel's interface.
#pragma once

#include <algorithm>
#include <cstddef>
#include <vector>

#include "kernel/patch.h"

namespace radquad::detail {

// Positions and normal projections of a patch's sample points, structure-of-arrays.
inline void placePoints(const Patch& patch, const double* __restrict u, const double* __restrict v,
                        std::size_t count, const Eigen::Vector3d& otherNormal,
                        std::vector<double>& xs, std::vector<double>& ys, std::vector<double>& zs,
                        std::vector<double>& ownNormalDots, std::vector<double>& otherNormalDots) {
  for (auto* column : {&xs, &ys, &zs, &ownNormalDots, &otherNormalDots}) column->resize(count);
  double* __restrict x = xs.data();
  double* __restrict y = ys.data();
  double* __restrict z = zs.data();
  double* __restrict ownNormalDot = ownNormalDots.data();
  double* __restrict otherNormalDot = otherNormalDots.data();
  const double ox = patch.origin.x(), oy = patch.origin.y(), oz = patch.origin.z();
  const double ax = patch.edgeU.x(), ay = patch.edgeU.y(), az = patch.edgeU.z();
  const double bx = patch.edgeV.x(), by = patch.edgeV.y(), bz = patch.edgeV.z();
  const double nx = patch.normal.x(), ny = patch.normal.y(), nz = patch.normal.z();
  const double mx = otherNormal.x(), my = otherNormal.y(), mz = otherNormal.z();
  for (std::size_t k = 0; k < count; ++k) {
    x[k] = ox + u[k] * ax + v[k] * bx;
    y[k] = oy + u[k] * ay + v[k] * by;
    z[k] = oz + u[k] * az + v[k] * bz;
    ownNormalDot[k] = nx * x[k] + ny * y[k] + nz * z[k];
    otherNormalDot[k] = mx * x[k] + my * y[k] + mz * z[k];
  }
}

// cos(theta) cos(theta') |d|^2 / |d|^4 with d = y - x:
// n_r.d = n_r.y - n_r.x and -n_s.d = n_s.x - n_s.y.
inline double kernelTimesPi(double dx, double dy, double dz, double receiverCos, double sourceCos) {
  const double r2 = dx * dx + dy * dy + dz * dz;
  const double c = std::max(receiverCos, 0.0) * std::max(sourceCos, 0.0);
  return c / (r2 * r2);
}

}  // namespace radquad::detail
