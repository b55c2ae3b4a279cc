#include "radiosity/link_integration.h"

#include <algorithm>
#include <cmath>

#include "kernel/legendre_basis.h"
#include "radiosity/visibility.h"

namespace radquad {
namespace {

bool pointOnPatch(const Eigen::Vector3d& point, const Patch& patch, double tolerance) {
  if (std::abs(patch.normal.dot(point - patch.origin)) > tolerance) return false;
  const Eigen::Vector2d uv = patch.parametersOf(point);
  const double u = uv.x(), v = uv.y();
  const double slackU = tolerance / patch.edgeU.norm(), slackV = tolerance / patch.edgeV.norm();
  return u >= -slackU && u <= 1.0 + slackU && v >= -slackV && v <= 1.0 + slackV;
}

// The part of an element over a rectangle of its parameter square.
Patch subPatch(const Patch& element, double u0, double v0, double du, double dv) {
  Patch piece = element;
  piece.origin = element.origin + u0 * element.edgeU + v0 * element.edgeV;
  piece.edgeU = du * element.edgeU;
  piece.edgeV = dv * element.edgeV;
  piece.area = du * dv * element.area;
  return piece;
}

// Whether a piece of `element` is more than twice as long as it is wide (physical lengths).
template <typename Square>
bool longPiece(const Patch& element, const Square& square) {
  const double lengthU = square.du * element.edgeU.norm();
  const double lengthV = square.dv * element.edgeV.norm();
  return lengthU > 2.0 * lengthV || lengthV > 2.0 * lengthU;
}

// The two halves of a long piece across its long side.
template <typename Square>
void halvePiece(const Patch& element, const Square& square, Square* halves) {
  const bool alongU = square.du * element.edgeU.norm() > square.dv * element.edgeV.norm();
  for (int h = 0; h < 2; ++h) {
    halves[h] = square;
    if (alongU) {
      halves[h].du = 0.5 * square.du;
      halves[h].u0 = square.u0 + h * halves[h].du;
    } else {
      halves[h].dv = 0.5 * square.dv;
      halves[h].v0 = square.v0 + h * halves[h].dv;
    }
  }
}

// Quadrant c = 2 cu + cv of a piece (the quadtree's child numbering).
template <typename Square>
void quarterPiece(const Square& square, Square* quadrants) {
  for (int c = 0; c < 4; ++c) {
    quadrants[c] = Square{square.u0 + (c / 2) * 0.5 * square.du,
                          square.v0 + (c % 2) * 0.5 * square.dv, 0.5 * square.du, 0.5 * square.dv};
  }
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

bool elementsNear(const Patch& a, const Patch& b) {
  // Radii: half the longer diagonal of each parallelogram.
  const double radiusA = 0.5 * std::max((a.edgeU + a.edgeV).norm(), (a.edgeU - a.edgeV).norm());
  const double radiusB = 0.5 * std::max((b.edgeU + b.edgeV).norm(), (b.edgeU - b.edgeV).norm());
  const double distance = (a.centre() - b.centre()).norm();
  return distance < kNearFactor * (radiusA + radiusB) || elementsTouch(a, b);
}

LinkIntegrationCounts LinkIntegrator::integrate(const Link& link, const GaussPointCounts& rule,
                                                const GaussTables& tables, int depth,
                                                bool isComposite,
                                                Eigen::Map<Eigen::MatrixXd> coupling) {
  LinkIntegrationCounts counts;
  if (!isComposite) {
    const GaussSide& receiverSide = tables.side(rule[0], rule[1]);
    const GaussSide& sourceSide = tables.side(rule[2], rule[3]);
    accumulator_.product(link, receiverSide.samples, receiverSide.basis, sourceSide.samples,
                         sourceSide.basis, piece_);
    coupling = piece_.coupling;
    counts.kernelEvaluations = piece_.kernelEvaluations;
    counts.raysCast = piece_.raysCast;
    return counts;
  }
  pieces_.clear();
  collectPieces(link.receiver, Square{}, link.source, Square{}, depth);
  // The pieces that share a receiver square form one product rule: that square's points
  // times the points of all its source squares. Grouping them makes fewer, larger products
  // (and fuller ray packets) than one product per piece.
  std::stable_sort(pieces_.begin(), pieces_.end(), [](const Piece& a, const Piece& b) {
    return a.receiver.key() > b.receiver.key();
  });
  const GaussSide& receiverSide = tables.side(rule[0], rule[1]);
  const GaussSide& sourceSide = tables.side(rule[2], rule[3]);
  const std::size_t sourcePoints = sourceSide.samples.size();
  coupling.setZero();
  for (std::size_t first = 0; first < pieces_.size();) {
    std::size_t last = first + 1;
    while (last < pieces_.size() && pieces_[last].receiver.key() == pieces_[first].receiver.key()) {
      ++last;
    }
    placeSide(receiverSide, rule[0], rule[1], pieces_[first].receiver, receiverPiece_, 0,
              receiverSide.samples.size());
    const std::size_t total = (last - first) * sourcePoints;
    for (std::size_t k = first; k < last; ++k) {
      placeSide(sourceSide, rule[2], rule[3], pieces_[k].source, sourcePiece_,
                (k - first) * sourcePoints, total);
    }
    // The whole elements' link: points in the pieces, the elements' basis functions.
    accumulator_.product(link, receiverPiece_.samples, receiverPiece_.basis, sourcePiece_.samples,
                         sourcePiece_.basis, piece_);
    coupling += piece_.coupling;
    counts.kernelEvaluations += piece_.kernelEvaluations;
    counts.raysCast += piece_.raysCast;
    first = last;
  }
  return counts;
}

// The side's points are the product of pointsU nodes along u and pointsV along v, point
// k = i * pointsV + j (radiosity/gauss_tables.cpp), so the basis values are products of
// phi_p(u_i) and phi_q(v_j), evaluated once per node.
void LinkIntegrator::placeSide(const GaussSide& side, int pointsU, int pointsV,
                               const Square& square, GaussSide& placed, std::size_t offset,
                               std::size_t total) {
  const int degree = side.basis.degree;
  const int orders = degree + 1;
  const int functions = side.basis.functions;
  const double area = square.du * square.dv;
  double alongU[GaussTables::kMaxPointsPerAxis][kMaxBasisDegree + 1];
  double alongV[GaussTables::kMaxPointsPerAxis][kMaxBasisDegree + 1];
  for (int i = 0; i < pointsU; ++i) {
    const double u = square.u0 + square.du * side.samples.u[std::size_t(i * pointsV)];
    shiftedLegendreValues(degree, u, alongU[i]);
  }
  for (int j = 0; j < pointsV; ++j) {
    const double v = square.v0 + square.dv * side.samples.v[std::size_t(j)];
    shiftedLegendreValues(degree, v, alongV[j]);
  }
  placed.samples.u.resize(total);
  placed.samples.v.resize(total);
  placed.samples.weight.resize(total);
  placed.basis.degree = degree;
  placed.basis.functions = functions;
  placed.basis.values.resize(total * std::size_t(functions));
  for (int i = 0; i < pointsU; ++i) {
    for (int j = 0; j < pointsV; ++j) {
      const std::size_t k = std::size_t(i * pointsV + j);
      const std::size_t out = offset + k;
      const double weight = area * side.samples.weight[k];
      placed.samples.u[out] = square.u0 + square.du * side.samples.u[k];
      placed.samples.v[out] = square.v0 + square.dv * side.samples.v[k];
      placed.samples.weight[out] = weight;
      double* row = placed.basis.values.data() + out * std::size_t(functions);
      for (int p = 0; p < orders; ++p) {
        const double wu = weight * alongU[i][p];
        for (int q = 0; q < orders; ++q) row[p * orders + q] = wu * alongV[j][q];
      }
    }
  }
}

void LinkIntegrator::collectPieces(const Patch& receiverElement, const Square& receiverSquare,
                                   const Patch& sourceElement, const Square& sourceSquare,
                                   int depth) {
  const Patch receiver = subPatch(receiverElement, receiverSquare.u0, receiverSquare.v0,
                                  receiverSquare.du, receiverSquare.dv);
  const Patch source =
      subPatch(sourceElement, sourceSquare.u0, sourceSquare.v0, sourceSquare.du, sourceSquare.dv);
  const bool receiverLong = longPiece(receiverElement, receiverSquare);
  const bool sourceLong = longPiece(sourceElement, sourceSquare);
  const bool near = elementsNear(receiver, source);
  const bool receiverCut = !near && straddlesPlane(source, receiver);
  const bool sourceCut = !near && straddlesPlane(receiver, source);
  if ((!near && !receiverCut && !sourceCut) ||
      (depth <= 0 && (!near || (!receiverLong && !sourceLong)))) {
    pieces_.push_back(Piece{receiverSquare, sourceSquare});
    return;
  }
  // Near pieces: long pieces are halved first (the other piece kept whole, no depth spent);
  // once both are nearly square, both are quartered, one level of depth. Pieces apart but cut
  // by the other's plane: the cut ones are quartered, one level of depth.
  Square receiverChildren[4], sourceChildren[4];
  int receiverCount = 1, sourceCount = 1, childDepth = depth;
  if (!near) {
    receiverChildren[0] = receiverSquare;
    sourceChildren[0] = sourceSquare;
    if (receiverCut) quarterPiece(receiverSquare, receiverChildren), receiverCount = 4;
    if (sourceCut) quarterPiece(sourceSquare, sourceChildren), sourceCount = 4;
    childDepth = depth - 1;
  } else if (receiverLong || sourceLong) {
    if (receiverLong) halvePiece(receiverElement, receiverSquare, receiverChildren), receiverCount = 2;
    else receiverChildren[0] = receiverSquare;
    if (sourceLong) halvePiece(sourceElement, sourceSquare, sourceChildren), sourceCount = 2;
    else sourceChildren[0] = sourceSquare;
  } else {
    quarterPiece(receiverSquare, receiverChildren);
    quarterPiece(sourceSquare, sourceChildren);
    receiverCount = sourceCount = 4;
    childDepth = depth - 1;
  }
  for (int cr = 0; cr < receiverCount; ++cr) {
    const Square& receiverChild = receiverChildren[cr];
    const Patch receiverPiece = subPatch(receiverElement, receiverChild.u0, receiverChild.v0,
                                         receiverChild.du, receiverChild.dv);
    for (int cs = 0; cs < sourceCount; ++cs) {
      const Square& sourceChild = sourceChildren[cs];
      const Patch sourcePiece =
          subPatch(sourceElement, sourceChild.u0, sourceChild.v0, sourceChild.du, sourceChild.dv);
      if (!mayExchange(receiverPiece, sourcePiece)) continue;
      collectPieces(receiverElement, receiverChild, sourceElement, sourceChild, childDepth);
    }
  }
}

}  // namespace radquad
