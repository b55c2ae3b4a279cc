#include "reference/point_polygon_form_factor.h"

#include <array>
#include <cmath>
#include <numbers>
#include <vector>

namespace radquad {

double pointToPatchFormFactor(const Eigen::Vector3d& x, const Eigen::Vector3d& n,
                              const Patch& source) {
  // One-sided source: seen from behind its plane, cos theta' <= 0 everywhere.
  if (source.normal.dot(x - source.origin) <= 0.0) return 0.0;
  const std::array<Eigen::Vector3d, 4> corners = {source.origin, source.origin + source.edgeU,
                                                  source.origin + source.edgeU + source.edgeV,
                                                  source.origin + source.edgeV};
  // Sutherland-Hodgman clip of the convex polygon to n.(p - x) >= 0 (cos theta >= 0).
  std::vector<Eigen::Vector3d> polygon;
  polygon.reserve(8);
  for (std::size_t i = 0; i < corners.size(); ++i) {
    const Eigen::Vector3d& a = corners[i];
    const Eigen::Vector3d& b = corners[(i + 1) % corners.size()];
    const double heightA = n.dot(a - x);
    const double heightB = n.dot(b - x);
    if (heightA >= 0.0) polygon.push_back(a);
    if ((heightA >= 0.0) != (heightB >= 0.0)) {
      polygon.push_back(a + (heightA / (heightA - heightB)) * (b - a));
    }
  }
  if (polygon.size() < 3) return 0.0;
  double sum = 0.0;
  for (std::size_t i = 0; i < polygon.size(); ++i) {
    const Eigen::Vector3d r0 = polygon[i] - x;
    const Eigen::Vector3d r1 = polygon[(i + 1) % polygon.size()] - x;
    const Eigen::Vector3d cross = r0.cross(r1);
    const double crossNorm = cross.norm();
    if (crossNorm == 0.0) continue;  // an edge through x's line of sight adds nothing
    const double gamma = std::atan2(crossNorm, r0.dot(r1));
    sum += n.dot(cross) / crossNorm * gamma;
  }
  // The vertex order fixes the sign; the polygon lies wholly in front of x, so the total is
  // of one sign.
  return std::fabs(sum) / (2.0 * std::numbers::pi);
}

}  // namespace radquad
