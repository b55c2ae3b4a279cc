// Link visibility classes, decided conservatively (a link with an occluder in the way is
// never called unoccluded):
//   1. Candidate occluders: the scene's patches, other than the link's own two, that are not
//      separated from the shaft (the convex hull of the two elements) by one of its
//      supporting planes: the receiver's plane, the source's plane (only points in front of
//      both matter: elsewhere the kernel is 0), the shaft's bounding box, and every plane
//      through an edge of one element and a corner of the other that has all eight corners
//      on one side (Haines and Wallace 1994, "Shaft culling for efficient ray-cast
//      radiosity"). A plane test can only fail to separate, never separate wrongly, so a
//      patch that meets the shaft is always a candidate.
//   2. No candidate: unoccluded. A candidate that covers the shaft (blocksShaft): occluded,
//      proven, without rays. Otherwise rays on a 4x4 by 4x4 grid of element points (the
//      pairs where the unoccluded kernel is positive): all blocked means occluded; anything
//      else, even all rays visible, is partial.
// A sub-link's shaft lies inside its parent's, so its candidates are a subset of the parent's.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "kernel/occluder_scene.h"
#include "kernel/patch.h"
#include "kernel/patch_intersection.h"
#include "radiosity/scene.h"

namespace radquad {

enum class LinkClass : std::uint8_t { kUnoccluded, kPartial, kOccluded };

const char* linkClassName(LinkClass visibility);

// Whether the unoccluded kernel can be positive anywhere: some source point strictly in
// front of the receiver's plane and some receiver point strictly in front of the source's.
bool mayExchange(const Patch& receiver, const Patch& source);

// cutByTangentPlane and straddlesPlane (links cut by a tangent plane): kernel/patch_intersection.h.

// Whether a partially visible link's visibility changes across each element: rays from the
// centres of the receiver's four quadrants to the source's centre (receiver), and from the
// receiver's centre to the source's quadrants' centres (source), where the unoccluded kernel
// is positive; an element varies when its rays disagree. `occluders` holds every patch (rays
// are shortened at both ends, so the link's own patches never block them).
struct VisibilityVariation {
  bool receiver = false, source = false;
};
VisibilityVariation visibilityVariation(const OccluderScene& occluders, const Patch& receiver,
                                        const Patch& source);

struct Classification {
  LinkClass visibility = LinkClass::kUnoccluded;
  // For an occluded link: whether one candidate provably blocks every segment between the
  // elements (blocksShaft, tried before any ray: then raysCast is 0); otherwise the class
  // rests on the rays alone.
  bool occlusionProven = false;
  std::vector<int> candidates;  // patch indices
  std::uint64_t raysCast = 0;
};

// Whether `occluder` blocks every segment from `receiver` to `source`: its plane strictly
// separates the two elements and the 16 points where the segments between their corners
// cross that plane lie inside it. The segments between two convex sets fill the convex hull
// of their union, whose section by a separating plane is the hull of those 16 points, so
// this is exact and conservative (a margin of 1e-9 of the size keeps it so under rounding).
bool blocksShaft(const Patch& occluder, const Patch& receiver, const Patch& source);

class VisibilityClassifier {
 public:
  // `occluders` holds every patch of `scene` (committed).
  VisibilityClassifier(const Scene& scene, const OccluderScene& occluders);

  static constexpr int kGridPoints = 4;  // per axis of each element

  // `parentCandidates`: the candidates of the parent link, or null for a top-level link
  // (then every patch but the two is tested).
  Classification classify(const Patch& receiver, int receiverPatch, const Patch& source,
                          int sourcePatch, const std::vector<int>* parentCandidates) const;

 private:
  struct Shaft;
  bool separated(Shaft& shaft, int patch) const;  // builds the shaft's planes when needed

  struct PatchBounds {
    std::array<Eigen::Vector3d, 4> corners;
    Eigen::Vector3d low, high;  // bounding box
  };

  const Scene& scene_;
  const OccluderScene& occluders_;
  std::vector<PatchBounds> bounds_;  // per patch of scene_
};

}  // namespace radquad
