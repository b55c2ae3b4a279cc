#include "radiosity/near_field.h"

#include <algorithm>
#include <cmath>

#include "kernel/legendre_basis.h"
#include "kernel/patch_intersection.h"
#include "radiosity/link_integration.h"
#include "quadrature/gauss_legendre.h"
#include "reference/source_moments.h"

namespace radquad {
namespace {

// The part of a patch over a rectangle of its parameter square.
Patch part(const Patch& patch, double u0, double v0, double du, double dv) {
  Patch piece = patch;
  piece.origin = patch.pointAt(u0, v0);
  piece.edgeU = du * patch.edgeU;
  piece.edgeV = dv * patch.edgeV;
  piece.area = du * dv * patch.area;
  return piece;
}

}  // namespace

// Whether a piece must be split whatever its estimates say: it is larger than its distance d
// to an edge of the visible source, and lies within the band where the inner integral
// changes, those receiver points whose distance to the edge is comparable to the edge's
// height h above the receiver's plane (d < 2 h; the edge of a source 1 cm above a receiver:
// I falls from 1 to 1/2 within about 1 cm of the edge's foot). Its points and its halves'
// could all miss that band and agree on a wrong value. Farther from the edge the integrand
// varies on the scale of the distance, with a magnitude that falls like h / d^2, and the
// piece's two estimates see it. An edge that touches the piece or lies in the receiver's plane (a
// shared edge, the line where the receiver's plane cuts the source) leaves the integrand
// bounded and continuous there, and the estimates see its variation too.
bool NearFieldIntegrator::mustSplit(const Piece& piece, int level) const {
  if (level >= kMaxForcedLevel) return false;
  const Patch region = part(*receiver_, piece.u0, piece.v0, piece.du, piece.dv);
  const double size = diameter(region);
  const Eigen::Vector3d centre = region.centre();
  // Larger than the visible source and nearer to it than its size, touching or not: pieces
  // of the source's size next to it (a large receiver touching a small source otherwise
  // integrates the shared edge's neighbourhood with a few points of its own scale).
  const bool larger = size > visibleDiameter_;
  for (std::size_t i = 0, n = visibleSource_.size(); i < n; ++i) {
    const Eigen::Vector3d& a = visibleSource_[i];
    const Eigen::Vector3d& b = visibleSource_[(i + 1) % n];
    const double distance = segmentToPatchDistance(a, b, region);
    if (!(distance < size)) continue;
    if (larger) return true;
    if (!(distance > kTouching * size) || !bandMatters_[i]) continue;
    const Eigen::Vector3d edge = b - a;
    const double t = std::clamp(edge.dot(centre - a) / edge.squaredNorm(), 0.0, 1.0);
    const double height = receiver_->normal.dot(a + t * edge - receiver_->origin);
    if (distance < 2.0 * std::abs(height)) return true;
  }
  return false;
}

// The piece's children: halves across its long side when it is more than twice as long as
// wide, else quarters.
int NearFieldIntegrator::children(const Piece& piece, Piece* out) const {
  const double lengthU = piece.du * receiver_->edgeU.norm();
  const double lengthV = piece.dv * receiver_->edgeV.norm();
  const double hu = 0.5 * piece.du, hv = 0.5 * piece.dv;
  if (lengthU > 2.0 * lengthV) {
    out[0] = {piece.u0, piece.v0, hu, piece.dv};
    out[1] = {piece.u0 + hu, piece.v0, hu, piece.dv};
    return 2;
  }
  if (lengthV > 2.0 * lengthU) {
    out[0] = {piece.u0, piece.v0, piece.du, hv};
    out[1] = {piece.u0, piece.v0 + hv, piece.du, hv};
    return 2;
  }
  for (int c = 0; c < 4; ++c) out[c] = {piece.u0 + (c / 2) * hu, piece.v0 + (c % 2) * hv, hu, hv};
  return 4;
}

// The Gauss product estimate of the piece's share of the coupling with `points` per axis.
void NearFieldIntegrator::estimate(const Piece& piece, int points, Eigen::MatrixXd& out) {
  const GaussLegendreRule& rule = gaussLegendreUnit(points);
  const int functions = basisFunctionCount(degree_);
  double inner[basisFunctionCount(kMaxBasisDegree)];
  double values[basisFunctionCount(kMaxBasisDegree)];
  out.setZero(functions, functions);
  for (int i = 0; i < points; ++i) {
    const double s = piece.u0 + piece.du * rule.nodes[std::size_t(i)];
    for (int j = 0; j < points; ++j) {
      const double t = piece.v0 + piece.dv * rule.nodes[std::size_t(j)];
      const double weight = scale_ * piece.du * piece.dv * rule.weights[std::size_t(i)] *
                            rule.weights[std::size_t(j)];
      const Eigen::Vector3d x = receiver_->pointAt(s, t);
      visibility_->visibleRings(x, rings_);
      moments_->compute(x, receiver_->normal, rings_, inner);
      tensorBasisValues(degree_, s, t, values);
      for (int b = 0; b < functions; ++b) {
        const double wb = weight * inner[b];
        for (int a = 0; a < functions; ++a) out(a, b) += wb * values[a];
      }
    }
  }
  counts_.points += std::uint64_t(points * points);
}

// Adds the piece's share to `total`: its estimates with points_ and points_ + 1 points per axis
// (their nodes interleave along both sides) are compared; where they agree within the piece's
// share (by area) of the tolerance, the finer one is kept, else the piece's children are.
void NearFieldIntegrator::refine(const Piece& piece, int level, Eigen::MatrixXd& total) {
  estimate(piece, points_, coarse_);
  estimate(piece, points_ + 1, fine_);
  if (tolerance_ < 0.0) {
    tolerance_ = relativeTolerance_ * std::max(coarse_.cwiseAbs().maxCoeff(),
                                               fine_.cwiseAbs().maxCoeff());
  }
  const double error = (fine_ - coarse_).cwiseAbs().maxCoeff();
  const bool forced = mustSplit(piece, level);
  if (!forced && (error <= tolerance_ * piece.du * piece.dv || level >= maxLevel_)) {
    total += fine_;
    ++counts_.pieces;
    return;
  }
  Piece parts[4];
  const int count = children(piece, parts);
  for (int c = 0; c < count; ++c) refine(parts[c], count == 4 ? level + 1 : level, total);
}

NearFieldIntegrator::Counts NearFieldIntegrator::integrate(
    const Link& link, const std::vector<std::vector<Eigen::Vector3d>>& polygons,
    const std::vector<int>& candidates, int degree, Eigen::Map<Eigen::MatrixXd> coupling) {
  ExactVisibility visibility(link, polygons, candidates);
  SourceMoments moments(link.source, degree, kInnerAccuracy);
  visibility_ = &visibility;
  moments_ = &moments;
  receiver_ = &link.receiver;
  degree_ = degree;
  // At least 2 points per axis, as the fixed product rules (radiosity/README.md).
  points_ = std::max(2, degree + 1);
  scale_ = std::sqrt(link.receiver.area / link.source.area);
  counts_ = Counts{};
  // S': the source in front of the receiver's plane (the same for every receiver point).
  const auto corners = link.source.corners();
  sourceCorners_.assign(corners.begin(), corners.end());
  clipConvexPolygon(sourceCorners_, link.receiver.normal,
                    -link.receiver.normal.dot(link.receiver.origin), visibleSource_);
  // An edge's band is worth resolving only where it can hold a share of the coupling above
  // the tolerance: its area, about twice the edge's height times its length, against the
  // receiver's (a light 1 mm under a ceiling: a band of 0.2% of a square metre).
  bandMatters_.assign(visibleSource_.size(), 0);
  for (std::size_t i = 0, n = visibleSource_.size(); i < n; ++i) {
    const Eigen::Vector3d& a = visibleSource_[i];
    const Eigen::Vector3d& b = visibleSource_[(i + 1) % n];
    const double height = std::max(std::abs(link.receiver.normal.dot(a - link.receiver.origin)),
                                   std::abs(link.receiver.normal.dot(b - link.receiver.origin)));
    bandMatters_[i] = 2.0 * height * (b - a).norm() > relativeTolerance_ * link.receiver.area;
  }
  visibleDiameter_ = 0.0;
  for (const Eigen::Vector3d& a : visibleSource_) {
    for (const Eigen::Vector3d& b : visibleSource_) {
      visibleDiameter_ = std::max(visibleDiameter_, (a - b).norm());
    }
  }
  Eigen::MatrixXd total = Eigen::MatrixXd::Zero(coupling.rows(), coupling.cols());
  tolerance_ = -1.0;  // set by the whole receiver's estimates
  refine(Piece{}, 0, total);
  coupling = total;
  visibility_ = nullptr;
  moments_ = nullptr;
  return counts_;
}

}  // namespace radquad
