#include "radiosity/visibility.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "kernel/coupling.h"

namespace radquad {
namespace {

using Vec = Eigen::Vector3d;


}  // namespace

const char* linkClassName(LinkClass visibility) {
  switch (visibility) {
    case LinkClass::kUnoccluded:
      return "unoccluded";
    case LinkClass::kPartial:
      return "partial";
    case LinkClass::kOccluded:
      return "occluded";
  }
  return "?";
}

bool mayExchange(const Patch& receiver, const Patch& source) {
  // Strictly in front, by a margin relative to the patches' size, so that coplanar or
  // edge-touching elements (zero kernel) do not link.
  const double scale = std::sqrt(std::max(receiver.area, source.area));
  const double margin = 1e-9 * scale;
  bool sourceInFront = false, receiverInFront = false;
  for (const Vec& point : source.corners()) {
    sourceInFront = sourceInFront || receiver.normal.dot(point - receiver.origin) > margin;
  }
  for (const Vec& point : receiver.corners()) {
    receiverInFront = receiverInFront || source.normal.dot(point - source.origin) > margin;
  }
  return sourceInFront && receiverInFront;
}

bool blocksShaft(const Patch& occluder, const Patch& receiver, const Patch& source) {
  const std::array<Vec, 4> rc = receiver.corners(), sc = source.corners();
  const double size = std::sqrt(std::max({occluder.area, receiver.area, source.area}));
  const double margin = 1e-9 * size;
  std::array<double, 4> hr, hs;
  for (int k = 0; k < 4; ++k) {
    hr[std::size_t(k)] = occluder.normal.dot(rc[std::size_t(k)] - occluder.origin);
    hs[std::size_t(k)] = occluder.normal.dot(sc[std::size_t(k)] - occluder.origin);
  }
  const bool receiverAbove = hr[0] > 0.0;
  for (int k = 0; k < 4; ++k) {
    const double r = receiverAbove ? hr[std::size_t(k)] : -hr[std::size_t(k)];
    const double s = receiverAbove ? -hs[std::size_t(k)] : hs[std::size_t(k)];
    if (!(r > margin) || !(s > margin)) return false;  // the plane does not separate them
  }
  // Inside the parallelogram: the crossing point's coordinates along its edges in [0, 1],
  // kept away from the border by the margin.
  const double slackU = margin / occluder.edgeU.norm(), slackV = margin / occluder.edgeV.norm();
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 4; ++j) {
      const double t = hr[std::size_t(i)] / (hr[std::size_t(i)] - hs[std::size_t(j)]);
      const Eigen::Vector2d uv = occluder.parametersOf(
          rc[std::size_t(i)] + t * (sc[std::size_t(j)] - rc[std::size_t(i)]));
      const double u = uv.x(), v = uv.y();
      if (!(u > slackU && u < 1.0 - slackU && v > slackV && v < 1.0 - slackV)) return false;
    }
  }
  return true;
}

VisibilityVariation visibilityVariation(const OccluderScene& occluders, const Patch& receiver,
                                        const Patch& source) {
  // The quadrants' centres of each element, seen from the other's centre: an element varies
  // when some of its rays are blocked and some not (pairs with a zero kernel do not count).
  // The (at most eight) rays go to Embree as one packet.
  thread_local SegmentBatch segments;
  segments.clear();
  int counted[2] = {0, 0};  // rays of the receiver's quadrants, then of the source's
  for (int side = 0; side < 2; ++side) {
    const Patch& varied = side == 0 ? receiver : source;
    const Vec centre = (side == 0 ? source : receiver).centre();
    for (int q = 0; q < 4; ++q) {
      const Vec point = varied.pointAt(0.25 + 0.5 * (q / 2), 0.25 + 0.5 * (q % 2));
      const Vec& from = side == 0 ? point : centre;
      const Vec& to = side == 0 ? centre : point;
      if (unoccludedKernel(receiver, from, source, to) <= 0.0) continue;
      segments.push(from, to - from);
      ++counted[side];
    }
  }
  if (segments.size() > 0) occluders.trace(segments);
  VisibilityVariation variation;
  std::size_t k = 0;
  for (int side = 0; side < 2; ++side) {
    int visible = 0, blocked = 0;
    for (int r = 0; r < counted[side]; ++r, ++k) (segments.visible(k) ? visible : blocked) += 1;
    (side == 0 ? variation.receiver : variation.source) = visible > 0 && blocked > 0;
  }
  return variation;
}

VisibilityClassifier::VisibilityClassifier(const Scene& scene, const OccluderScene& occluders)
    : scene_(scene), occluders_(occluders) {
  // Every link tests its candidates' corners and boxes: computed once.
  bounds_.reserve(scene.patches.size());
  for (const ScenePatch& patch : scene.patches) {
    PatchBounds bounds;
    bounds.corners = patch.patch.corners();
    bounds.low = bounds.corners[0];
    bounds.high = bounds.corners[0];
    for (const Vec& point : bounds.corners) {
      bounds.low = bounds.low.cwiseMin(point);
      bounds.high = bounds.high.cwiseMax(point);
    }
    bounds_.push_back(bounds);
  }
}

// A link's shaft: the convex hull of its two elements, with its bounding box and its
// supporting planes through an edge of one element and a corner of the other (those with the
// whole hull on one side, n.x <= offset + tolerance). Built once per link and tested against
// every candidate; the planes pair by pair, only as far as the candidates that survive the
// cheaper tests (box, the elements' planes, which settle most candidates of most links) need
// them: a candidate is separated as soon as one plane has it beyond.
struct VisibilityClassifier::Shaft {
  const Patch* receiver = nullptr;
  const Patch* source = nullptr;
  std::array<Vec, 8> hull;  // the receiver's corners, then the source's
  Vec low, high;
  double tolerance = 0.0;
  int pairsBuilt = 0;  // (edge, corner) pairs whose planes are built, of 2 x 4 x 4
  int planes = 0;
  std::array<Vec, 64> normals;  // 2 sides x 4 edges x 4 corners x 2 orientations at most
  std::array<double, 64> offsets;

  Shaft(const Patch& r, const Patch& s) : receiver(&r), source(&s) {
    const std::array<Vec, 4> rc = r.corners(), sc = s.corners();
    hull = {rc[0], rc[1], rc[2], rc[3], sc[0], sc[1], sc[2], sc[3]};
    low = hull[0];
    high = hull[0];
    for (const Vec& point : hull) {
      low = low.cwiseMin(point);
      high = high.cwiseMax(point);
    }
    tolerance = 1e-9 * std::max((high - low).norm(), 1e-300);
  }

  static constexpr int kPairs = 32;

  // The planes of the next (edge, corner) pair, in a fixed order (side, edge, corner): an
  // edge of one element and a corner of the other, either orientation that has the whole
  // hull behind it (both, where the hull is flat).
  void buildNextPair() {
    const int pair = pairsBuilt++;
    const int side = pair / 16;
    const std::size_t k = std::size_t(pair / 4 % 4), c = std::size_t(pair % 4);
    const std::size_t edges = side == 0 ? 0 : 4, apexes = side == 0 ? 4 : 0;
    const Vec& a = hull[edges + k];
    const Vec& b = hull[edges + (k + 1) % 4];
    const Vec& apex = hull[apexes + c];
    Vec normal = (b - a).cross(apex - a);
    const double lengthSquared = normal.squaredNorm();
    // Degenerate (the corner on the edge's line): |n| <= 1e-12 |b - a| |apex - a|. The
    // squares decide it without three square roots except within 1e-9 of the threshold,
    // where the roots are taken as the test is written (rounding moves either side by far
    // less), so the planes are exactly those of the test itself.
    const double bound = 1e-24 * (b - a).squaredNorm() * (apex - a).squaredNorm();
    if (lengthSquared <= bound * (1.0 - 1e-9)) return;
    const double length = std::sqrt(lengthSquared);
    if (lengthSquared < bound * (1.0 + 1e-9) &&
        length <= 1e-12 * (b - a).norm() * (apex - a).norm()) {
      return;
    }
    normal /= length;
    const double offset = normal.dot(a);
    double lowest = normal.dot(hull[0]), highest = lowest;
    for (const Vec& point : hull) {
      const double height = normal.dot(point);
      lowest = std::min(lowest, height);
      highest = std::max(highest, height);
    }
    if (!(highest > offset + tolerance)) add(normal, offset);
    if (!(-lowest > -offset + tolerance)) add(-normal, -offset);
  }

  void add(const Vec& normal, double offset) {
    normals[std::size_t(planes)] = normal;
    offsets[std::size_t(planes)] = offset;
    ++planes;
  }
};

bool VisibilityClassifier::separated(Shaft& shaft, int patch) const {
  const PatchBounds& bounds = bounds_[std::size_t(patch)];
  const std::array<Vec, 4>& occluder = bounds.corners;
  const double tolerance = shaft.tolerance;
  // Bounding boxes.
  for (int axis = 0; axis < 3; ++axis) {
    if (bounds.low[axis] >= shaft.high[axis] - tolerance) return true;
    if (bounds.high[axis] <= shaft.low[axis] + tolerance) return true;
  }
  // Behind (or on) the receiver's or the source's plane: the segments that carry energy
  // start on one element and end strictly in front of it, so they never reach there.
  for (const Patch* plane : {shaft.receiver, shaft.source}) {
    bool allBehind = true;
    for (const Vec& point : occluder) {
      allBehind = allBehind && plane->normal.dot(point - plane->origin) <= tolerance;
    }
    if (allBehind) return true;
  }
  // The occluder wholly on or beyond one of the shaft's supporting planes: those built for
  // the link's earlier candidates, then the rest, built as far as this occluder needs (a
  // link whose candidates are all settled early builds only the planes that settle them).
  const auto beyondPlane = [&](int k) {
    const Vec& normal = shaft.normals[std::size_t(k)];
    const double offset = shaft.offsets[std::size_t(k)];
    bool beyond = true;
    for (const Vec& point : occluder) beyond = beyond && !(normal.dot(point) < offset + tolerance);
    return beyond;
  };
  for (int k = 0; k < shaft.planes; ++k) {
    if (beyondPlane(k)) return true;
  }
  while (shaft.pairsBuilt < Shaft::kPairs) {
    const int first = shaft.planes;
    shaft.buildNextPair();
    for (int k = first; k < shaft.planes; ++k) {
      if (beyondPlane(k)) return true;
    }
  }
  return false;
}

Classification VisibilityClassifier::classify(const Patch& receiver, int receiverPatch,
                                              const Patch& source, int sourcePatch,
                                              const std::vector<int>* parentCandidates) const {
  Classification result;
  Shaft shaft(receiver, source);
  auto consider = [&](int patch) {
    if (patch == receiverPatch || patch == sourcePatch) return;
    if (!separated(shaft, patch)) result.candidates.push_back(patch);
  };
  if (parentCandidates) {
    for (int patch : *parentCandidates) consider(patch);
  } else {
    for (int patch = 0; patch < int(scene_.patches.size()); ++patch) consider(patch);
  }
  if (result.candidates.empty()) {
    result.visibility = LinkClass::kUnoccluded;
    return result;
  }
  // One candidate that blocks every segment between the elements settles the class without
  // rays: occluded, provably.
  for (int patch : result.candidates) {
    if (blocksShaft(scene_.patches[std::size_t(patch)].patch, receiver, source)) {
      result.visibility = LinkClass::kOccluded;
      result.occlusionProven = true;
      return result;
    }
  }
  // Rays between stratum centres of the two elements, where the kernel is positive. One
  // visible ray settles the class (partial), so the pairs are traced a packet at a time in
  // an order that spreads each packet over both elements (round c pairs receiver point i
  // with source point (i + c) mod 16, so every round meets all points of each), stopping at
  // the first packet with a visible ray; only an occluded link traces every pair.
  constexpr int n = kGridPoints;
  constexpr int points = n * n;
  // Where every corner of each element lies in front of the other's plane by far more than
  // rounding (1e-9 of the largest coordinate), every pair of their points has both cosines
  // positive (each cosine is affine along the other element), and the kernel's sign need not
  // be tested pair by pair: the same pairs are traced.
  // The shaft holds both elements' corners (receiver's first) and their box already.
  const double extent = std::max(shaft.low.cwiseAbs().maxCoeff(), shaft.high.cwiseAbs().maxCoeff());
  const double margin = 1e-9 * extent;
  // (Within these extents no kernel value of a facing pair underflows to zero.)
  bool facing = extent > 1e-100 && extent < 1e30;
  for (std::size_t k = 0; k < 4; ++k) {
    facing = facing && receiver.normal.dot(shaft.hull[4 + k] - receiver.origin) > margin &&
             source.normal.dot(shaft.hull[k] - source.origin) > margin;
  }
  std::array<Vec, points> x, y;
  for (int i = 0; i < points; ++i) {
    x[std::size_t(i)] = receiver.pointAt((i / n + 0.5) / n, (i % n + 0.5) / n);
    y[std::size_t(i)] = source.pointAt((i / n + 0.5) / n, (i % n + 0.5) / n);
  }
  thread_local SegmentBatch segments;
  segments.clear();
  result.visibility = LinkClass::kOccluded;
  auto traceBatch = [&] {
    occluders_.trace(segments);
    result.raysCast += segments.size();
    for (std::size_t k = 0; k < segments.size(); ++k) {
      if (segments.visible(k)) return true;
    }
    segments.clear();
    return false;
  };
  for (int round = 0; round < points; ++round) {
    for (int i = 0; i < points; ++i) {
      const Vec& from = x[std::size_t(i)];
      const Vec& to = y[std::size_t((i + round) % points)];
      if (!facing && unoccludedKernel(receiver, from, source, to) <= 0.0) continue;
      segments.push(from, to - from);
      if (segments.size() == 16 && traceBatch()) {
        result.visibility = LinkClass::kPartial;
        return result;
      }
    }
  }
  if (segments.size() > 0 && traceBatch()) result.visibility = LinkClass::kPartial;
  // No pair faces the other way round: nothing to trace, kept partial (conservative).
  if (result.raysCast == 0) result.visibility = LinkClass::kPartial;
  return result;
}

}  // namespace radquad
