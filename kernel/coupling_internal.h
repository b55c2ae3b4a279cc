// Helpers shared by the product and the scattered coupling paths (kernel/coupling.cpp,
// kernel/scattered_coupling.cpp); not part of the kernel's interface.
#pragma once

#include <algorithm>
#include <cstddef>
#include <vector>

#include "kernel/patch.h"

namespace radquad::detail {

// A patch's parametrisation and normals unpacked, for placing sample points.
struct PatchFrame {
  double ox, oy, oz, ax, ay, az, bx, by, bz;  // origin, edge_u, edge_v
  double nx, ny, nz, mx, my, mz;              // own normal, the other patch's normal

  PatchFrame(const Patch& patch, const Eigen::Vector3d& otherNormal)
      : ox(patch.origin.x()),
        oy(patch.origin.y()),
        oz(patch.origin.z()),
        ax(patch.edgeU.x()),
        ay(patch.edgeU.y()),
        az(patch.edgeU.z()),
        bx(patch.edgeV.x()),
        by(patch.edgeV.y()),
        bz(patch.edgeV.z()),
        nx(patch.normal.x()),
        ny(patch.normal.y()),
        nz(patch.normal.z()),
        mx(otherNormal.x()),
        my(otherNormal.y()),
        mz(otherNormal.z()) {}

  // x(u,v) = o + u a + v b and its projections on the own and the other normal. Every path
  // places points through this one expression, so they cast bit-identical rays.
  void place(double u, double v, double& x, double& y, double& z, double& ownNormalDot,
             double& otherNormalDot) const {
    x = ox + u * ax + v * bx;
    y = oy + u * ay + v * by;
    z = oz + u * az + v * bz;
    ownNormalDot = nx * x + ny * y + nz * z;
    otherNormalDot = mx * x + my * y + mz * z;
  }
};

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
  const PatchFrame frame(patch, otherNormal);
  // The columns never overlap (GCC does not see it through the restrict locals).
#pragma GCC ivdep
  for (std::size_t k = 0; k < count; ++k) {
    frame.place(u[k], v[k], x[k], y[k], z[k], ownNormalDot[k], otherNormalDot[k]);
  }
}

// cos(theta) cos(theta') |d|^2 / |d|^4 with d = y - x:
// n_r.d = n_r.y - n_r.x and -n_s.d = n_s.x - n_s.y.
// A pair whose clamped cosines vanish contributes 0, whatever its distance: in particular two
// coincident points (d = 0, where the expression is 0/0) are a set of measure zero, not NaN.
inline double kernelTimesPi(double dx, double dy, double dz, double receiverCos, double sourceCos) {
  const double r2 = dx * dx + dy * dy + dz * dz;
  const double c = std::max(receiverCos, 0.0) * std::max(sourceCos, 0.0);
  return c > 0.0 ? c / (r2 * r2) : 0.0;
}

// The one predicate that decides whether a pair needs a visibility ray: its unoccluded kernel
// is positive. Every path counts and fills its ray buffers with it (a NaN kernel, which
// kernelTimesPi no longer produces from finite points, would need no ray either way).
inline bool needsRay(double kernelValue) {
  return kernelValue > 0.0;
}

}  // namespace radquad::detail
