// The polar method of the exact gold's inner integral (source_moments.h): the moments of the
// visible part of the source seen from a receiver point, edge by edge of its rings, at every
// degree; at degrees 0-3 the edge nodes go through the lane batches of radial_moments.h.
#include "reference/source_moments.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "kernel/legendre_basis.h"
#include "quadrature/gauss_legendre.h"
#include "reference/radial_moments.h"

namespace radquad {
namespace {

using detail::kLanes;
using detail::kMaxPower;

// Gauss points along a ring edge's piece. The pieces keep the integrand's singularity at
// least a piece's length from its centre (Bernstein ellipse parameter at least 2 + sqrt(3)):
// 12 points err by about 1e-14 relative; 8 points by at most 2e-7 on points as close to the
// source as a twentieth of its size (tests/reference/source_moments_test.cpp), where the
// polynomial weights cancel most. Where x is beside the source and near its plane, the
// edges' terms cancel (the source is seen at grazing angles, its moments are small) and the
// error relative to x's own moments grows: over 20,000 random points and visible rings a
// degree, up to 1.3e-5 (degree 1), 1.1e-4 (degree 2) and 2.2e-3 (degree 3). On a grazing
// link at the study's tolerance (exact_gold_test.cpp) the gold's actual error was then 3
// times its estimate at degree 3 and within it at degrees 1 and 2: degree 3 takes the 12
// points at any accuracy.
int edgePointsFor(double accuracy, int degree) {
  return accuracy < 1e-6 || degree >= 3 ? 12 : 8;
}
constexpr int kMaxEdgePoints = 12;

// Coefficients in rho of the orthonormal shifted Legendre polynomials phi_0..phi_d at
// t = t0 + t1 rho: coefficients[i * (d + 1) + k] multiplies rho^k.
void legendreAlongRay(int d, double t0, double t1, double* coefficients) {
  const int stride = d + 1;
  if (d <= 3) {
    // Taylor coefficients phi_i^(k)(t0) t1^k / k! of phi_1 = sqrt3 (2t - 1),
    // phi_2 = sqrt5 (6t^2 - 6t + 1), phi_3 = sqrt7 (20t^3 - 30t^2 + 12t - 1).
    constexpr double s3 = 1.7320508075688772, s5 = 2.2360679774997898, s7 = 2.6457513110645907;
    coefficients[0] = 1.0;
    for (int k = 1; k < stride; ++k) coefficients[k] = 0.0;
    if (d == 0) return;
    double* c1 = coefficients + stride;
    c1[0] = s3 * (2.0 * t0 - 1.0);
    c1[1] = s3 * 2.0 * t1;
    for (int k = 2; k < stride; ++k) c1[k] = 0.0;
    if (d == 1) return;
    const double t1s = t1 * t1;
    double* c2 = coefficients + 2 * stride;
    c2[0] = s5 * ((6.0 * t0 - 6.0) * t0 + 1.0);
    c2[1] = s5 * (12.0 * t0 - 6.0) * t1;
    c2[2] = s5 * 6.0 * t1s;
    if (d == 2) return;
    c2[3] = 0.0;
    double* c3 = coefficients + 3 * stride;
    c3[0] = s7 * (((20.0 * t0 - 30.0) * t0 + 12.0) * t0 - 1.0);
    c3[1] = s7 * ((60.0 * t0 - 60.0) * t0 + 12.0) * t1;
    c3[2] = s7 * (60.0 * t0 - 30.0) * t1s;
    c3[3] = s7 * 20.0 * t1s * t1;
    return;
  }
  std::fill(coefficients, coefficients + stride * stride, 0.0);
  // P_k(z), z = 2t - 1 = z0 + z1 rho.
  const double z0 = 2.0 * t0 - 1.0, z1 = 2.0 * t1;
  double previous[kMaxBasisDegree + 2] = {}, current[kMaxBasisDegree + 2] = {},
         next[kMaxBasisDegree + 2] = {};
  current[0] = 1.0;
  for (int k = 0; k <= d; ++k) {
    const double norm = std::sqrt(2.0 * k + 1.0);
    for (int p = 0; p <= k; ++p) coefficients[k * stride + p] = norm * current[p];
    if (k == d) break;
    // P_(k+1) = ((2k+1) z P_k - k P_(k-1)) / (k+1)
    for (int p = 0; p <= k + 1; ++p) {
      const double zp = z0 * current[p] + (p > 0 ? z1 * current[p - 1] : 0.0);
      next[p] = ((2.0 * k + 1.0) * zp - k * previous[p]) / (k + 1.0);
    }
    for (int p = 0; p <= k + 1; ++p) {
      previous[p] = current[p];
      current[p] = next[p];
    }
  }
}

// kLanes edge nodes of one receiver point (degree <= 3): each step of accumulateBatch is one
// loop over the lanes with no branch.
struct NodeBatch {
  double wx[kLanes], wy[kLanes], weight[kLanes];
  int count = 0;
};

// `batch` holds kLanes nodes (those past its count padded by the caller: pad()).
template <int D>
void accumulateBatch(const NodeBatch& batch, double H, double a0, double nx, double ny,
                     const Eigen::Matrix2d& toParameters, bool loose, double* laneT) {
  constexpr int P = 2 * D + 2;  // highest radial power
  constexpr int stride = D + 1;
  const double invH = 1.0 / H;
  const double t00 = toParameters(0, 0), t01 = toParameters(0, 1), t10 = toParameters(1, 0),
               t11 = toParameters(1, 1);
  double su[kLanes], sv[kLanes], a1[kLanes], X[kLanes];
  for (int k = 0; k < kLanes; ++k) {
    const double wx = batch.wx[k], wy = batch.wy[k];
    const double inverseR = 1.0 / std::sqrt(wx * wx + wy * wy);
    const double ox = wx * inverseR, oy = wy * inverseR;
    su[k] = t00 * ox + t01 * oy;
    sv[k] = t10 * ox + t11 * oy;
    a1[k] = nx * ox + ny * oy;
    X[k] = invH / inverseR;
  }
  double j[P + 1][kLanes];
  detail::laneRadialMoments<P>(X, loose, j);
  // J_m = H^(m-3) j_m; Q_k = weight (a0 J_(k+1) + a1 J_(k+2)); T[k][l] += su^k sv^l Q_(k+l).
  double Q[2 * D + 1][kLanes];
  double scale = invH * invH;  // H^(m-2) at m = 0: the scale of J_(m+1)
  for (int m = 0; m <= 2 * D; ++m) {
    const double low = a0 * scale, high = scale * H;
    for (int k = 0; k < kLanes; ++k) {
      Q[m][k] = batch.weight[k] * (low * j[m + 1][k] + a1[k] * high * j[m + 2][k]);
    }
    scale *= H;
  }
  // Per lane: the lanes are summed once per receiver point (sumLanes).
  double powerU[kLanes];
  for (int k = 0; k < kLanes; ++k) powerU[k] = 1.0;
  for (int u = 0; u <= D; ++u) {
    double powerUV[kLanes];
    for (int k = 0; k < kLanes; ++k) powerUV[k] = powerU[k];
    for (int v = 0; v <= D; ++v) {
      double* lanes = laneT + (u * stride + v) * kLanes;
      for (int k = 0; k < kLanes; ++k) lanes[k] += powerUV[k] * Q[u + v][k];
      for (int k = 0; k < kLanes; ++k) powerUV[k] *= sv[k];
    }
    for (int k = 0; k < kLanes; ++k) powerU[k] *= su[k];
  }
}

// Fills the lanes past the batch's count (at least one is used) with copies of the first
// node and no weight: finite values that add exactly nothing, in the first node's branch.
void pad(NodeBatch& batch) {
  for (int k = batch.count; k < kLanes; ++k) {
    batch.wx[k] = batch.wx[0];
    batch.wy[k] = batch.wy[0];
    batch.weight[k] = 0.0;
  }
}

}  // namespace

SourceMoments::SourceMoments(const Patch& source, int degree, double accuracy)
    : source_(source),
      degree_(degree),
      functions_(basisFunctionCount(degree)),
      edgeRule_(gaussLegendreUnit(edgePointsFor(accuracy, degree))),
      loose_(edgePointsFor(accuracy, degree) == 8) {
  validateBasisDegree(degree);
  axisX_ = source.edgeU.normalized();
  axisY_ = source.normal.cross(axisX_);
  toPlane_ << source.edgeU.dot(axisX_), source.edgeV.dot(axisX_), source.edgeU.dot(axisY_),
      source.edgeV.dot(axisY_);
  toParameters_ = toPlane_.inverse();
}

void SourceMoments::compute(const Eigen::Vector3d& x, const Eigen::Vector3d& n,
                            const VisibleRings& visible, double* out) const {
  if (degree_ == 0) {
    out[0] = formFactor(x, n, visible);
    return;
  }
  computePolar(x, n, visible, out);
}

void SourceMoments::computePolar(const Eigen::Vector3d& x, const Eigen::Vector3d& n,
                                 const VisibleRings& visible, double* out) const {
  switch (degree_) {
    case 0: return polar<0>(x, n, visible, out);
    case 1: return polar<1>(x, n, visible, out);
    case 2: return polar<2>(x, n, visible, out);
    case 3: return polar<3>(x, n, visible, out);
    default: return polar<-1>(x, n, visible, out);
  }
}

// D >= 0: the degree as a compile-time constant (loops unrolled); D = -1: degree_ at run time.
template <int D>
void SourceMoments::polar(const Eigen::Vector3d& x, const Eigen::Vector3d& n,
                          const VisibleRings& visible, double* out) const {
  const int d = D >= 0 ? D : degree_;
  const int stride = d + 1;
  std::fill(out, out + functions_, 0.0);
  if (visible.empty()) return;
  const Eigen::Vector3d offset = x - source_.origin;
  const double H = source_.normal.dot(offset);
  if (!(H > 0.0)) return;
  // The foot p0 in plane coordinates and in (u, v).
  const Eigen::Vector2d foot(offset.dot(axisX_), offset.dot(axisY_));
  const Eigen::Vector2d footUV = toParameters_ * foot;
  const double a0 = -H * n.dot(source_.normal);  // n_r . (p0 - x)
  const double nx = n.dot(axisX_), ny = n.dot(axisY_);
  const int maxPower = 2 * d + 2;
  const GaussLegendreRule& rule = edgeRule_;
  const int edgePoints = int(rule.nodes.size());
  const double* nodes = rule.nodes.data();
  const double* weights = rule.weights.data();
  const double kernelScale = H / std::numbers::pi;

  double J[kMaxPower + 1];
  double Q[kMaxPower + 1];
  // phi_i(t0 + t1 rho) = sum_k C[i][k] (t1 rho)^k with C[i][k] = phi_i^(k)(t0) / k!: the
  // Taylor coefficients at the foot depend on x alone, the powers of the step on the node.
  // So I[i][j] = sum_(k, l) CU[i][k] CV[j][l] T[k][l], with
  //   T[k][l] = sum_nodes weight su^k sv^l Q[k + l]
  // accumulated over the nodes and the small products taken once per point.
  double CU[(kMaxBasisDegree + 1) * (kMaxBasisDegree + 1)];
  double CV[(kMaxBasisDegree + 1) * (kMaxBasisDegree + 1)];
  double T[(kMaxBasisDegree + 1) * (kMaxBasisDegree + 1)];
  legendreAlongRay(d, footUV.x(), 1.0, CU);
  legendreAlongRay(d, footUV.y(), 1.0, CV);
  std::fill(T, T + stride * stride, 0.0);

  // One node: direction w from p0 (|w| = R, the ring edge's point), weight `weight`.
  auto node = [&](const Eigen::Vector2d& w, double weight) {
    const double R = w.norm();
    const Eigen::Vector2d omega = w / R;
    const Eigen::Vector2d step = toParameters_ * omega;  // d(u, v) / d rho
    const double a1 = nx * omega.x() + ny * omega.y();   // d(n_r . (y - x)) / d rho
    radialMoments(R, H, maxPower, J);
    for (int k = 0; k <= 2 * d; ++k) Q[k] = weight * (a0 * J[k + 1] + a1 * J[k + 2]);
    double powerU = 1.0;
    for (int k = 0; k <= d; ++k) {
      double powerUV = powerU;
      for (int l = 0; l <= d; ++l) {
        T[k * stride + l] += powerUV * Q[k + l];
        powerUV *= step.y();
      }
      powerU *= step.x();
    }
  };

  // Degrees 0-3: the nodes in batches (accumulateBatch); higher ones one at a time.
  constexpr bool kBatched = D >= 0 && D <= 3;
  NodeBatch batch;
  constexpr int kLaneEntries = kBatched ? (D + 1) * (D + 1) * kLanes : 1;
  double laneT[kLaneEntries] = {};
  // One edge (uvA, uvB) of a ring or of the outline, in (u, v), and the sign it counts with.
  const auto edge = [&](const Eigen::Vector2d& uvA, const Eigen::Vector2d& uvB, double edgeSign) {
    const Eigen::Vector2d a = toPlane_ * uvA - foot;
    const Eigen::Vector2d b = toPlane_ * uvB - foot;
    const double length = (b - a).norm();
    if (length == 0.0) return;
    const Eigen::Vector2d direction = (b - a) / length;
    const double distance = a.x() * direction.y() - a.y() * direction.x();  // signed
    // The triangle has no area: |distance| <= 1e-15 max(|a|, |b|, H), in squares.
    if (distance * distance <= 1e-30 * std::max({a.squaredNorm(), b.squaredNorm(), H * H})) {
      return;
    }
    const Eigen::Vector2d closest = a - a.dot(direction) * direction;
    const double sa = a.dot(direction), sb = sa + length;
    // Signed triangle (p0, a, b): integrand along the edge |d| / R^2 Phi(R), sign of d.
    const double sign = distance > 0.0 ? 1.0 : -1.0;
    const double reach2 = distance * distance + H * H;
    // Pieces [s0, s1] of the edge, bisected until no longer than the distance from their
    // centre to the nearest singularity, at +-i sqrt(d^2 + H^2) from the closest point.
    double stack[2 * 64];
    int top = 0;
    stack[top++] = sa;
    stack[top++] = sb;
    while (top > 0) {
      const double s1 = stack[--top];
      const double s0 = stack[--top];
      const double centre = 0.5 * (s0 + s1), half = 0.5 * (s1 - s0);
      if (half * half > 0.25 * (centre * centre + reach2) && top + 4 <= 2 * 64) {
        stack[top++] = s0;
        stack[top++] = centre;
        stack[top++] = centre;
        stack[top++] = s1;
        continue;
      }
      // The piece's nodes in one loop over them (vector instructions), then to the batch.
      const double factor = edgeSign * sign * std::fabs(distance) * (s1 - s0);
      double wx[kMaxEdgePoints], wy[kMaxEdgePoints], weight[kMaxEdgePoints];
      for (int k = 0; k < edgePoints; ++k) {
        const double s = s0 + (s1 - s0) * nodes[k];
        wx[k] = closest.x() + s * direction.x();
        wy[k] = closest.y() + s * direction.y();
        weight[k] = factor * weights[k] / (wx[k] * wx[k] + wy[k] * wy[k]);
      }
      for (int k = 0; k < edgePoints; ++k) {
        if constexpr (kBatched) {
          batch.wx[batch.count] = wx[k];
          batch.wy[batch.count] = wy[k];
          batch.weight[batch.count] = weight[k];
          if (++batch.count == kLanes) {
            accumulateBatch<D>(batch, H, a0, nx, ny, toParameters_, loose_, laneT);
            batch.count = 0;
          }
        } else {
          node(Eigen::Vector2d(wx[k], wy[k]), weight[k]);
        }
      }
    }
  };
  for (std::size_t r = 0; r < visible.count(); ++r) {
    const SourceRing& ring = visible.ring(r);
    const std::size_t count = ring.size();
    for (std::size_t e = 0; e < count; ++e) edge(ring[e], ring[(e + 1) % count], visible.sign(r));
  }
  for (std::size_t s = 0; s < visible.segmentCount(); ++s) {
    edge(visible.segmentStart(s), visible.segmentEnd(s), visible.segmentSign(s));
  }
  if constexpr (kBatched) {
    if (batch.count > 0) {
      pad(batch);
      accumulateBatch<D>(batch, H, a0, nx, ny, toParameters_, loose_, laneT);
    }
    detail::sumLanes(laneT, stride * stride, T);
  }
  // I[i][j] = kernelScale sum_k CU[i][k] sum_l CV[j][l] T[k][l] (C lower triangular).
  for (int i = 0; i <= d; ++i) {
    for (int j = 0; j <= d; ++j) {
      double sum = 0.0;
      for (int k = 0; k <= i; ++k) {
        double inner = 0.0;
        for (int l = 0; l <= j; ++l) inner += CV[j * stride + l] * T[k * stride + l];
        sum += CU[i * stride + k] * inner;
      }
      out[i * stride + j] = kernelScale * sum;
    }
  }
}

}  // namespace radquad
