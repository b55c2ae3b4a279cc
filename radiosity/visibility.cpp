#include "radiosity/visibility.h"

#include <array>
#include <cmath>

#include "kernel/coupling.h"

namespace radquad {
namespace {

using Vec = Eigen::Vector3d;

std::array<Vec, 4> corners(const Patch& patch) {
  return {patch.origin, patch.origin + patch.edgeU, patch.origin + patch.edgeU + patch.edgeV,
          patch.origin + patch.edgeV};
}

// Whether every point of `outside` lies on or beyond the plane (n, offset), n.x >= offset -
// tolerance counts as "on". Returns false if the plane does not bound `hull` on the other side.
bool planeSeparates(const Vec& normal, double offset, const std::array<Vec, 8>& hull,
                    const std::array<Vec, 4>& outside, double tolerance) {
  for (const Vec& point : hull) {
    if (normal.dot(point) > offset + tolerance) return false;  // not a supporting plane
  }
  for (const Vec& point : outside) {
    if (normal.dot(point) < offset + tolerance) return false;
  }
  return true;
}

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
  for (const Vec& point : corners(source)) {
    sourceInFront = sourceInFront || receiver.normal.dot(point - receiver.origin) > margin;
  }
  for (const Vec& point : corners(receiver)) {
    receiverInFront = receiverInFront || source.normal.dot(point - source.origin) > margin;
  }
  return sourceInFront && receiverInFront;
}

VisibilityClassifier::VisibilityClassifier(const Scene& scene, const OccluderScene& occluders)
    : scene_(scene), occluders_(occluders) {}

bool VisibilityClassifier::separated(const Patch& receiver, const Patch& source, int patch) const {
  const std::array<Vec, 4> occluder = corners(scene_.patches[std::size_t(patch)].patch);
  const std::array<Vec, 4> r = corners(receiver), s = corners(source);
  const std::array<Vec, 8> hull = {r[0], r[1], r[2], r[3], s[0], s[1], s[2], s[3]};
  Vec low = hull[0], high = hull[0];
  for (const Vec& point : hull) {
    low = low.cwiseMin(point);
    high = high.cwiseMax(point);
  }
  const double tolerance = 1e-9 * std::max((high - low).norm(), 1e-300);
  // Bounding boxes.
  Vec occluderLow = occluder[0], occluderHigh = occluder[0];
  for (const Vec& point : occluder) {
    occluderLow = occluderLow.cwiseMin(point);
    occluderHigh = occluderHigh.cwiseMax(point);
  }
  for (int axis = 0; axis < 3; ++axis) {
    if (occluderLow[axis] >= high[axis] - tolerance) return true;
    if (occluderHigh[axis] <= low[axis] + tolerance) return true;
  }
  // Behind (or on) the receiver's or the source's plane: the segments that carry energy
  // start on one element and end strictly in front of it, so they never reach there.
  for (const Patch* plane : {&receiver, &source}) {
    bool allBehind = true;
    for (const Vec& point : occluder) {
      allBehind = allBehind && plane->normal.dot(point - plane->origin) <= tolerance;
    }
    if (allBehind) return true;
  }
  // Shaft planes through an edge of one element and a corner of the other.
  for (int side = 0; side < 2; ++side) {
    const std::array<Vec, 4>& edges = side == 0 ? r : s;
    const std::array<Vec, 4>& apexes = side == 0 ? s : r;
    for (int k = 0; k < 4; ++k) {
      const Vec& a = edges[std::size_t(k)];
      const Vec& b = edges[std::size_t((k + 1) % 4)];
      for (const Vec& apex : apexes) {
        Vec normal = (b - a).cross(apex - a);
        const double length = normal.norm();
        if (length <= 1e-12 * (b - a).norm() * (apex - a).norm()) continue;
        normal /= length;
        // Orient the normal away from the hull (try both orientations).
        if (planeSeparates(normal, normal.dot(a), hull, occluder, tolerance)) return true;
        if (planeSeparates(-normal, -normal.dot(a), hull, occluder, tolerance)) return true;
      }
    }
  }
  return false;
}

Classification VisibilityClassifier::classify(const Patch& receiver, int receiverPatch,
                                              const Patch& source, int sourcePatch,
                                              const std::vector<int>* parentCandidates) const {
  Classification result;
  auto consider = [&](int patch) {
    if (patch == receiverPatch || patch == sourcePatch) return;
    if (!separated(receiver, source, patch)) result.candidates.push_back(patch);
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
  // Rays between stratum centres of the two elements, where the kernel is positive. One
  // visible ray settles the class (partial), so the pairs are traced a packet at a time in
  // an order that spreads each packet over both elements (round c pairs receiver point i
  // with source point (i + c) mod 16, so every round meets all points of each), stopping at
  // the first packet with a visible ray; only an occluded link traces every pair.
  constexpr int n = kGridPoints;
  constexpr int points = n * n;
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
      if (unoccludedKernel(receiver, from, source, to) <= 0.0) continue;
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
