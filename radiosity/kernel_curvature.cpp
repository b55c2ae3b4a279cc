#include "radiosity/kernel_curvature.h"

#include <cmath>

#include "kernel/coupling.h"

namespace radquad {

double midpointRelativeError(const Patch& receiver, const Patch& source, bool alongU) {
  const Eigen::Vector3d x = receiver.centre();
  const Eigen::Vector3d c = source.centre();
  const Eigen::Vector3d half = 0.5 * (alongU ? source.edgeU : source.edgeV);
  const double g0 = unoccludedKernel(receiver, x, source, c);
  const double plus = unoccludedKernel(receiver, x, source, c + half);
  const double minus = unoccludedKernel(receiver, x, source, c - half);
  if (!(g0 > 0.0)) return plus + minus > 0.0 ? 1.0 : 0.0;
  return std::abs(plus + minus - 2.0 * g0) / (6.0 * g0);
}

}  // namespace radquad
