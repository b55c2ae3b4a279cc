#include "radiosity/link_integration.h"

#include <cmath>

#include "kernel/legendre_basis.h"
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

LinkIntegrationCounts LinkIntegrator::integrate(const Link& link, const std::array<int, 4>& rule,
                                                const GaussTables& tables, int depth,
                                                Eigen::Map<Eigen::MatrixXd> coupling) {
  LinkIntegrationCounts counts;
  if (depth <= 0 || !elementsNear(link.receiver, link.source)) {
    const GaussSide& receiverSide = tables.side(rule[0], rule[1]);
    const GaussSide& sourceSide = tables.side(rule[2], rule[3]);
    accumulator_.product(link, receiverSide.samples, receiverSide.basis, sourceSide.samples,
                         sourceSide.basis, piece_);
    coupling = piece_.coupling;
    counts.kernelEvaluations = piece_.kernelEvaluations;
    counts.raysCast = piece_.raysCast;
    return counts;
  }
  coupling.setZero();
  placedReceiver_ = false;  // a new link: its receiver rule or element may differ
  addPieces(link, link.receiver, Square{}, link.source, Square{}, depth, rule, tables, coupling,
            counts);
  return counts;
}

// The side's points are the product of pointsU nodes along u and pointsV along v, point
// k = i * pointsV + j (radiosity/gauss_tables.cpp), so the basis values are products of
// phi_p(u_i) and phi_q(v_j), evaluated once per node.
void LinkIntegrator::placeSide(const GaussSide& side, int pointsU, int pointsV,
                               const Square& square, GaussSide& placed) {
  const int degree = side.basis.degree;
  const int orders = degree + 1;
  const int functions = side.basis.functions;
  const std::size_t points = side.samples.size();
  const double area = square.size * square.size;
  double alongU[GaussTables::kMaxPointsPerAxis][kMaxBasisDegree + 1];
  double alongV[GaussTables::kMaxPointsPerAxis][kMaxBasisDegree + 1];
  for (int i = 0; i < pointsU; ++i) {
    const double u = square.u0 + square.size * side.samples.u[std::size_t(i * pointsV)];
    shiftedLegendreValues(degree, u, alongU[i]);
  }
  for (int j = 0; j < pointsV; ++j) {
    const double v = square.v0 + square.size * side.samples.v[std::size_t(j)];
    shiftedLegendreValues(degree, v, alongV[j]);
  }
  placed.samples.u.resize(points);
  placed.samples.v.resize(points);
  placed.samples.weight.resize(points);
  placed.basis.degree = degree;
  placed.basis.functions = functions;
  placed.basis.values.resize(points * std::size_t(functions));
  for (int i = 0; i < pointsU; ++i) {
    for (int j = 0; j < pointsV; ++j) {
      const std::size_t k = std::size_t(i * pointsV + j);
      const double weight = area * side.samples.weight[k];
      placed.samples.u[k] = square.u0 + square.size * side.samples.u[k];
      placed.samples.v[k] = square.v0 + square.size * side.samples.v[k];
      placed.samples.weight[k] = weight;
      double* row = placed.basis.values.data() + k * std::size_t(functions);
      for (int p = 0; p < orders; ++p) {
        const double wu = weight * alongU[i][p];
        for (int q = 0; q < orders; ++q) row[p * orders + q] = wu * alongV[j][q];
      }
    }
  }
}

void LinkIntegrator::addPieces(const Link& link, const Patch& receiver,
                               const Square& receiverSquare, const Patch& source,
                               const Square& sourceSquare, int depth,
                               const std::array<int, 4>& rule, const GaussTables& tables,
                               Eigen::Map<Eigen::MatrixXd>& coupling,
                               LinkIntegrationCounts& counts) {
  if (depth <= 0 || !elementsNear(receiver, source)) {
    // Consecutive pieces often share the receiver square (the loops below): place it once.
    if (!placedReceiver_ || receiverSquare.u0 != placedSquare_.u0 ||
        receiverSquare.v0 != placedSquare_.v0 || receiverSquare.size != placedSquare_.size) {
      placeSide(tables.side(rule[0], rule[1]), rule[0], rule[1], receiverSquare, receiverPiece_);
      placedReceiver_ = true;
      placedSquare_ = receiverSquare;
    }
    placeSide(tables.side(rule[2], rule[3]), rule[2], rule[3], sourceSquare, sourcePiece_);
    // The whole elements' link: points in the pieces, the elements' basis functions.
    accumulator_.product(link, receiverPiece_.samples, receiverPiece_.basis, sourcePiece_.samples,
                         sourcePiece_.basis, piece_);
    coupling += piece_.coupling;
    counts.kernelEvaluations += piece_.kernelEvaluations;
    counts.raysCast += piece_.raysCast;
    return;
  }
  // Quadrant c = 2 cu + cv, as quadrant() above.
  auto childSquare = [](const Square& square, int c) {
    const double half = 0.5 * square.size;
    return Square{square.u0 + (c / 2) * half, square.v0 + (c % 2) * half, half};
  };
  for (int cr = 0; cr < 4; ++cr) {
    const Patch receiverQuadrant = quadrant(receiver, cr);
    const Square receiverChild = childSquare(receiverSquare, cr);
    for (int cs = 0; cs < 4; ++cs) {
      const Patch sourceQuadrant = quadrant(source, cs);
      if (!mayExchange(receiverQuadrant, sourceQuadrant)) continue;
      addPieces(link, receiverQuadrant, receiverChild, sourceQuadrant,
                childSquare(sourceSquare, cs), depth - 1, rule, tables, coupling, counts);
    }
  }
}

}  // namespace radquad
