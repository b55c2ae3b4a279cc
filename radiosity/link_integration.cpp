#include "radiosity/link_integration.h"

#include <cmath>

#include "radiosity/visibility.h"

namespace radquad {
namespace {

bool pointOnPatch(const Eigen::Vector3d& point, const Patch& patch, double tolerance) {
  const Eigen::Vector3d r = point - patch.origin;
  if (std::abs(patch.normal.dot(r)) > tolerance) return false;
  const double aa = patch.edgeU.squaredNorm(), ab = patch.edgeU.dot(patch.edgeV);
  const double bb = patch.edgeV.squaredNorm();
  const double ar = patch.edgeU.dot(r), br = patch.edgeV.dot(r);
  const double determinant = aa * bb - ab * ab;
  const double u = (bb * ar - ab * br) / determinant, v = (aa * br - ab * ar) / determinant;
  const double slackU = tolerance / std::sqrt(aa), slackV = tolerance / std::sqrt(bb);
  return u >= -slackU && u <= 1.0 + slackU && v >= -slackV && v <= 1.0 + slackV;
}

// Quadrant c = 2 cu + cv of a parallelogram (the quadtree's child numbering).
Patch quadrant(const Patch& patch, int c) {
  Patch child = patch;
  child.edgeU = 0.5 * patch.edgeU;
  child.edgeV = 0.5 * patch.edgeV;
  child.origin = patch.origin + (c / 2) * child.edgeU + (c % 2) * child.edgeV;
  child.area = 0.25 * patch.area;
  return child;
}

}  // namespace

bool elementsTouch(const Patch& a, const Patch& b) {
  const double tolerance = 1e-9 * std::sqrt(std::max(a.area, b.area));
  for (const Patch* one : {&a, &b}) {
    const Patch& other = one == &a ? b : a;
    const Eigen::Vector3d corners[4] = {one->origin, one->origin + one->edgeU,
                                        one->origin + one->edgeU + one->edgeV,
                                        one->origin + one->edgeV};
    for (const Eigen::Vector3d& corner : corners) {
      if (pointOnPatch(corner, other, tolerance)) return true;
    }
  }
  return false;
}

bool elementsNear(const Patch& a, const Patch& b) {
  // Radii: half the longer diagonal of each parallelogram.
  const double radiusA = 0.5 * std::max((a.edgeU + a.edgeV).norm(), (a.edgeU - a.edgeV).norm());
  const double radiusB = 0.5 * std::max((b.edgeU + b.edgeV).norm(), (b.edgeU - b.edgeV).norm());
  const double distance = (a.centre() - b.centre()).norm();
  return distance < kNearFactor * (radiusA + radiusB) || elementsTouch(a, b);
}

void integrateLink(const Link& link, const std::array<int, 4>& rule, const GaussTables& tables,
                   const TwoScale& twoScale, int depth, CouplingAccumulator& accumulator,
                   LinkIntegrationResult& result) {
  const int functions = (twoScale.degree() + 1) * (twoScale.degree() + 1);
  if (depth <= 0 || !elementsNear(link.receiver, link.source)) {
    const GaussSide& receiverSide = tables.side(rule[0], rule[1]);
    const GaussSide& sourceSide = tables.side(rule[2], rule[3]);
    LinkIntegral integral;
    accumulator.product(link, receiverSide.samples, receiverSide.basis, sourceSide.samples,
                        sourceSide.basis, integral);
    result.coupling = std::move(integral.coupling);
    result.kernelEvaluations += integral.kernelEvaluations;
    result.raysCast += integral.raysCast;
    return;
  }
  // K = sum_cr T_cr^T (sum_cs K_(cr,cs) T_cs), with coefficient-wise products (the
  // matrices are at most 16 x 16: the blocked product's packing would cost more).
  Eigen::MatrixXd total = Eigen::MatrixXd::Zero(functions, functions);
  Eigen::MatrixXd inner(functions, functions);
  LinkIntegrationResult piece;
  for (int cr = 0; cr < 4; ++cr) {
    const Patch receiver = quadrant(link.receiver, cr);
    inner.setZero();
    bool any = false;
    for (int cs = 0; cs < 4; ++cs) {
      const Patch source = quadrant(link.source, cs);
      if (!mayExchange(receiver, source)) continue;
      const Link sub{receiver, source, link.occluders};
      integrateLink(sub, rule, tables, twoScale, depth - 1, accumulator, piece);
      inner.noalias() += piece.coupling.lazyProduct(twoScale.child(cs));
      any = true;
    }
    if (any) total.noalias() += twoScale.child(cr).transpose().lazyProduct(inner);
  }
  result.coupling = std::move(total);
  result.kernelEvaluations += piece.kernelEvaluations;
  result.raysCast += piece.raysCast;
}

}  // namespace radquad
