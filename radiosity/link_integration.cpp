#include "radiosity/link_integration.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "kernel/patch_intersection.h"

namespace radquad {
namespace {

bool pointOnPatch(const Eigen::Vector3d& point, const Patch& patch, double tolerance) {
  if (std::abs(patch.normal.dot(point - patch.origin)) > tolerance) return false;
  const Eigen::Vector2d uv = patch.parametersOf(point);
  const double u = uv.x(), v = uv.y();
  const double slackU = tolerance / patch.edgeU.norm(), slackV = tolerance / patch.edgeV.norm();
  return u >= -slackU && u <= 1.0 + slackU && v >= -slackV && v <= 1.0 + slackV;
}

}  // namespace

bool elementsTouch(const Patch& a, const Patch& b) {
  const double tolerance = 1e-9 * std::sqrt(std::max(a.area, b.area));
  for (const Patch* one : {&a, &b}) {
    const Patch& other = one == &a ? b : a;
    for (const Eigen::Vector3d& corner : one->corners()) {
      if (pointOnPatch(corner, other, tolerance)) return true;
    }
  }
  return false;
}

double diameter(const Patch& p) {
  return std::max((p.edgeU + p.edgeV).norm(), (p.edgeU - p.edgeV).norm());
}

double separationRatio(const Patch& a, const Patch& b) {
  return (a.centre() - b.centre()).norm() / (0.5 * (diameter(a) + diameter(b)));
}

double planeGap(const Patch& a, const Patch& b) {
  const auto oneSided = [](const Patch& plane, const Patch& other) {
    double low = std::numeric_limits<double>::infinity(), high = -low;
    for (const Eigen::Vector3d& corner : other.corners()) {
      const double d = plane.normal.dot(corner - plane.origin);
      low = std::min(low, d);
      high = std::max(high, d);
    }
    return low > 0.0 ? low : (high < 0.0 ? -high : 0.0);
  };
  return std::max(oneSided(a, b), oneSided(b, a));
}

bool nearField(const Patch& receiver, const Patch& source) {
  return separationRatio(receiver, source) < kNearFactor || cutByTangentPlane(receiver, source) ||
         elementsTouch(receiver, source);
}

LinkIntegrationCounts LinkIntegrator::integrate(const Link& link, const GaussPointCounts& rule,
                                                const GaussTables& tables,
                                                Eigen::Map<Eigen::MatrixXd> coupling) {
  const GaussSide& receiverSide = tables.side(rule[0], rule[1]);
  const GaussSide& sourceSide = tables.side(rule[2], rule[3]);
  accumulator_.product(link, receiverSide.samples, receiverSide.basis, sourceSide.samples,
                       sourceSide.basis, piece_);
  coupling = piece_.coupling;
  LinkIntegrationCounts counts;
  counts.kernelEvaluations = piece_.kernelEvaluations;
  counts.raysCast = piece_.raysCast;
  return counts;
}

}  // namespace radquad
