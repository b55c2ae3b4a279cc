#include "radiosity/kernel_curvature.h"

#include <algorithm>
#include <cmath>

namespace radquad {

double clampedKernelTimesPi(const Patch& receiver, const Eigen::Vector3d& x, const Patch& source,
                            const Eigen::Vector3d& y) {
  const Eigen::Vector3d d = y - x;
  const double r2 = d.squaredNorm();
  const double cosines = std::max(receiver.normal.dot(d), 0.0) * std::max(-source.normal.dot(d), 0.0);
  return cosines > 0.0 ? cosines / (r2 * r2) : 0.0;
}

double midpointRelativeError(const Patch& receiver, const Patch& source, bool alongU) {
  const Eigen::Vector3d x = receiver.centre();
  const Eigen::Vector3d c = source.centre();
  const Eigen::Vector3d half = 0.5 * (alongU ? source.edgeU : source.edgeV);
  const double g0 = clampedKernelTimesPi(receiver, x, source, c);
  const double plus = clampedKernelTimesPi(receiver, x, source, c + half);
  const double minus = clampedKernelTimesPi(receiver, x, source, c - half);
  if (!(g0 > 0.0)) return plus + minus > 0.0 ? 1.0 : 0.0;
  return std::abs(plus + minus - 2.0 * g0) / (6.0 * g0);
}

}  // namespace radquad
