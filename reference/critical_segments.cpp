#include "reference/critical_segments.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>

#include "reference/exact_visibility.h"

namespace radquad {
namespace {

// An interval of a line's parameter lambda, narrowed by affine constraints c0 + c1 lambda >= 0.
struct LineInterval {
  double low = -std::numeric_limits<double>::infinity();
  double high = std::numeric_limits<double>::infinity();

  void require(double c0, double c1) {
    if (c1 == 0.0) {
      if (c0 < 0.0) high = low = 0.0, empty = true;
      return;
    }
    const double root = -c0 / c1;
    if (c1 > 0.0) {
      low = std::max(low, root);
    } else {
      high = std::min(high, root);
    }
  }
  bool empty = false;
};

// The line alpha s + beta t = gamma of the receiver's parameter plane, as p0 + lambda d with
// |d| = 1; false when (alpha, beta) vanishes (the event plane parallel to the receiver's).
struct ParameterLine {
  Eigen::Vector2d p0, d;
};

bool parameterLine(double alpha, double beta, double gamma, double scale, ParameterLine& line) {
  const double norm2 = alpha * alpha + beta * beta;
  if (!(norm2 > 1e-24 * scale * scale)) return false;
  line.p0 = Eigen::Vector2d(alpha, beta) * (gamma / norm2);
  line.d = Eigen::Vector2d(-beta, alpha) / std::sqrt(norm2);
  return true;
}

// Narrows `interval` to the unit square and appends the segment if any length is left.
void clipToSquare(const ParameterLine& line, LineInterval interval,
                  std::vector<ReceiverSegment>& out) {
  for (int axis = 0; axis < 2; ++axis) {
    interval.require(line.p0[axis], line.d[axis]);         // coordinate >= 0
    interval.require(1.0 - line.p0[axis], -line.d[axis]);  // coordinate <= 1
  }
  if (interval.empty || !(interval.high - interval.low > 1e-12)) return;
  auto clamp01 = [](Eigen::Vector2d p) { return p.cwiseMax(0.0).cwiseMin(1.0); };
  out.push_back({clamp01(line.p0 + interval.low * line.d),
                 clamp01(line.p0 + interval.high * line.d)});
}

class SegmentFinder {
 public:
  SegmentFinder(const Patch& receiver, double scale) : receiver_(receiver), scale_(scale) {}

  // Receiver points x with x, p and a point e of [e1, e2] collinear and the nearer of p and
  // e between x and the farther: `vertexNearer` when p lies between x and e.
  void vertexEdge(const Eigen::Vector3d& p, const Eigen::Vector3d& e1, const Eigen::Vector3d& e2,
                  bool vertexNearer, std::vector<ReceiverSegment>& out) const {
    const Eigen::Vector3d m = (e1 - p).cross(e2 - p);
    const double mNorm = m.norm();
    if (!(mNorm > 1e-12 * scale_ * scale_)) return;  // p on the edge's line
    const Eigen::Vector3d normal = m / mNorm;
    ParameterLine line;
    if (!parameterLine(normal.dot(receiver_.edgeU), normal.dot(receiver_.edgeV),
                       normal.dot(p - receiver_.origin), std::max(receiver_.edgeU.norm(), receiver_.edgeV.norm()), line)) {
      return;
    }
    // x(lambda) = X0 + lambda D on the receiver's plane and in the event plane.
    const Eigen::Vector3d x0 = receiver_.pointAt(line.p0.x(), line.p0.y());
    const Eigen::Vector3d direction = line.d.x() * receiver_.edgeU + line.d.y() * receiver_.edgeV;
    // The cone with apex p spanned by d1, d2 (a, b >= 0): x - p = a d1 + b d2.
    const Eigen::Vector3d d1 = vertexNearer ? Eigen::Vector3d(p - e1) : Eigen::Vector3d(e1 - p);
    const Eigen::Vector3d d2 = vertexNearer ? Eigen::Vector3d(p - e2) : Eigen::Vector3d(e2 - p);
    const double denominator = d1.cross(d2).dot(normal);
    if (denominator == 0.0) return;
    const Eigen::Vector3d offset = x0 - p;
    const double a0 = offset.cross(d2).dot(normal) / denominator;
    const double a1 = direction.cross(d2).dot(normal) / denominator;
    const double b0 = d1.cross(offset).dot(normal) / denominator;
    const double b1 = d1.cross(direction).dot(normal) / denominator;
    LineInterval interval;
    interval.require(a0, a1);
    interval.require(b0, b1);
    // The edge nearer: x beyond it as seen from p, a + b >= 1.
    if (!vertexNearer) interval.require(a0 + b0 - 1.0, a1 + b1);
    clipToSquare(line, interval, out);
  }

  // The line where the receiver's plane meets the plane normal . y + offset = 0.
  void planeLine(const Eigen::Vector3d& normal, const Eigen::Vector3d& pointOnPlane,
                 std::vector<ReceiverSegment>& out) const {
    ParameterLine line;
    if (!parameterLine(normal.dot(receiver_.edgeU), normal.dot(receiver_.edgeV),
                       normal.dot(pointOnPlane - receiver_.origin),
                       std::max(receiver_.edgeU.norm(), receiver_.edgeV.norm()), line)) {
      return;
    }
    clipToSquare(line, LineInterval{}, out);
  }

 private:
  const Patch& receiver_;
  double scale_;
};

}  // namespace

std::vector<ReceiverSegment> criticalSegments(
    const Patch& receiver, const Patch& source,
    const std::vector<std::vector<Eigen::Vector3d>>& occluders) {
  // The link's size (not its coordinates' magnitude): the largest distance from the
  // receiver's origin to a corner of either patch.
  double scale = 0.0;
  for (const auto& c : receiver.corners()) scale = std::max(scale, (c - receiver.origin).norm());
  for (const auto& c : source.corners()) scale = std::max(scale, (c - receiver.origin).norm());
  scale = std::max(scale, 1e-300);
  const SegmentFinder finder(receiver, scale);
  std::vector<ReceiverSegment> segments;
  finder.planeLine(source.normal, source.origin, segments);

  const Eigen::Vector3d& nr = receiver.normal;
  const double receiverOffset = -nr.dot(receiver.origin);
  const double sourceOffset = -source.normal.dot(source.origin);
  // Polygon 0: the source in front of the receiver's plane; then the occluders clipped to the
  // slab in front of both planes (nothing outside it can stand between x and the source).
  std::vector<std::vector<Eigen::Vector3d>> polygons;
  std::vector<Eigen::Vector3d> clipped, twice;
  const auto corners = source.corners();
  clipConvexPolygon({corners.begin(), corners.end()}, nr, receiverOffset, clipped);
  if (clipped.size() < 3) return segments;
  polygons.push_back(clipped);
  for (const auto& polygon : occluders) {
    clipConvexPolygon(polygon, nr, receiverOffset, twice);
    clipConvexPolygon(twice, source.normal, sourceOffset, clipped);
    if (clipped.size() < 3) continue;
    polygons.push_back(clipped);
    // Seen edge-on from x in its own plane, an occluder's shadow has no area and grows as
    // |distance| on either side: a kink along the line where its plane meets the receiver's
    // (and, for an occluder standing on the receiver's plane, the edge it stands on).
    Eigen::Vector3d normal = Eigen::Vector3d::Zero();
    for (std::size_t k = 1; k + 1 < clipped.size(); ++k) {
      normal += (clipped[k] - clipped[0]).cross(clipped[k + 1] - clipped[0]);
    }
    if (normal.norm() > 0.0) finder.planeLine(normal.normalized(), clipped[0], segments);
  }
  for (std::size_t i = 0; i < polygons.size(); ++i) {
    for (std::size_t j = 0; j < polygons.size(); ++j) {
      if (i == j) continue;
      const auto& vertices = polygons[i];
      const auto& edges = polygons[j];
      for (const auto& p : vertices) {
        for (std::size_t k = 0, n = edges.size(); k < n; ++k) {
          const auto& e1 = edges[k];
          const auto& e2 = edges[(k + 1) % n];
          // The source (polygon 0) is always the farthest: a source vertex behind an occluder
          // edge, an occluder vertex in front of a source edge; two occluders either way.
          if (i != 0) finder.vertexEdge(p, e1, e2, true, segments);
          if (j != 0) finder.vertexEdge(p, e1, e2, false, segments);
        }
      }
    }
  }
  return segments;
}

std::vector<double> crossingsAt(const std::vector<ReceiverSegment>& segments, double s) {
  std::vector<double> breaks = {0.0, 1.0};
  for (const auto& segment : segments) {
    const double s0 = segment.a.x(), s1 = segment.b.x();
    if (std::abs(s1 - s0) < 1e-14) continue;
    const double f = (s - s0) / (s1 - s0);
    if (f < 0.0 || f > 1.0) continue;
    breaks.push_back(segment.a.y() + f * (segment.b.y() - segment.a.y()));
  }
  return breaks;
}

std::vector<ReceiverSegment> contactSegments(
    const Patch& receiver, const std::vector<std::vector<Eigen::Vector3d>>& occluders) {
  const Eigen::Vector3d& nr = receiver.normal;
  const double offset = -nr.dot(receiver.origin);
  std::vector<ReceiverSegment> segments;
  std::vector<Eigen::Vector3d> front, on;
  for (const auto& polygon : occluders) {
    // The part in front of the receiver's plane; its vertices within the clip's slack of the
    // plane are where it meets the plane (none above it: it lies in the plane, or behind).
    clipConvexPolygon(polygon, nr, offset, front);
    const double slack = planeSlack(nr, offset, polygonReach(polygon));
    on.clear();
    bool above = false;
    for (const auto& p : front) {
      if (std::abs(nr.dot(p) + offset) <= slack) {
        on.push_back(p);
      } else {
        above = true;
      }
    }
    if (!above || on.size() < 2) continue;
    // The convex polygon meets the plane in the segment between its two farthest points.
    std::size_t a = 0, b = 0;
    for (std::size_t i = 0; i < on.size(); ++i) {
      for (std::size_t j = i + 1; j < on.size(); ++j) {
        if ((on[i] - on[j]).squaredNorm() > (on[a] - on[b]).squaredNorm()) a = i, b = j;
      }
    }
    const Eigen::Vector2d p = receiver.parametersOf(on[a]), q = receiver.parametersOf(on[b]);
    const double length = (q - p).norm();
    if (!(length > 0.0)) continue;
    LineInterval interval;
    interval.low = 0.0;
    interval.high = length;
    clipToSquare(ParameterLine{p, (q - p) / length}, interval, segments);
  }
  return segments;
}

}  // namespace radquad
