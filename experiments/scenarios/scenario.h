// Scenario generation for the study (docs/design.md, "The study"): pairs of patches drawn
// deterministically from a seed over ranges of element size, distance, relative
// orientation and occluder complexity. Each candidate link is a pure function of
// (ranges, class, seed); whether a partial candidate qualifies (visible fraction in
// (0.05, 0.95) by the reference's rays) is decided by the study runner.
//
// Geometry (lengths in the units of the patches; L = the largest side of the two patches):
// - receiver: an a x b rectangle centred at the origin in the plane z = 0, normal +z;
// - sizes: with probability `mixed_fraction` the four sides are independent, log-uniform in
//   [min_side, max_side]; otherwise both patches are the same square of such a side;
// - distance D = L times a factor log-uniform in [min_distance_factor, max_distance_factor];
// - "parallel": the source faces the receiver at height D, offset laterally by up to L/4,
//   spun about its normal; "perpendicular": the source stands in a plane x = const beyond
//   the receiver's edge, facing it, its centre D from that edge at an elevation of 20 to 70
//   degrees (lifted if needed so it never touches the receiver's plane); "tilted": the
//   parallel layout with each patch rotated about a random in-plane axis by up to
//   `max_tilt_degrees` (redrawn until each patch lies wholly in front of the other).
// - occluders (partial class only), placed in the beam between the patch centres:
//   "one_blocker" one parallelogram of side 0.3L..L; "several_blockers" 2..6 smaller ones;
//   "slats" a grille of 5..15 thin parallel strips (sometimes crossed by a second set);
//   "soup" `soup_triangles` small random triangles (sides up to about 0.1L) in a box.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "kernel/link_geometry.h"
#include "kernel/occluder_scene.h"
#include "kernel/patch.h"

namespace radquad {

// The study's classes of links (docs/study.md): unoccluded, partially occluded, and singular
// (touching, or cut by the other's plane: scene-derived links only; never generated).
enum class StudyClass { unoccluded, partial, singular };
enum class Orientation { parallel, perpendicular, tilted };
// `scene`: the patches of a scene around a scene-derived link (experiments/study/scene_links.h);
// never generated, so not a name the geometry ranges accept.
enum class OccluderKind { none, oneBlocker, severalBlockers, slats, soup, scene };

const char* studyClassName(StudyClass linkClass);
const char* orientationName(Orientation orientation);
const char* occluderKindName(OccluderKind kind);

struct GeometryRanges {
  double minSide = 0.1;
  double maxSide = 1.0;
  double mixedFraction = 0.5;
  double minDistanceFactor = 0.25;
  double maxDistanceFactor = 4.0;
  std::vector<Orientation> orientations = {Orientation::parallel, Orientation::perpendicular,
                                           Orientation::tilted};
  double maxTiltDegrees = 75.0;
  std::vector<OccluderKind> occluders = {OccluderKind::oneBlocker, OccluderKind::severalBlockers,
                                         OccluderKind::slats, OccluderKind::soup};
  int soupTriangles = 1000;
};

// Parses the "geometry" object of a study config (every key optional; unknown keys are an
// error). `where` names it in messages.
GeometryRanges parseGeometryRanges(const nlohmann::json& value, const std::string& where);
nlohmann::json geometryRangesToJson(const GeometryRanges& ranges);

// A generated link: its geometry (blockers and slats as parallelograms, a soup as triangles)
// and how it was drawn.
struct GeneratedLink : LinkGeometry {
  Orientation orientation = Orientation::parallel;
  OccluderKind occluderKind = OccluderKind::none;
  double distanceFactor = 0.0;  // D / L
};

// The candidate link of `linkClass` drawn from `seed`. Unoccluded links have no occluders.
GeneratedLink generateLink(const GeometryRanges& ranges, StudyClass linkClass, std::uint64_t seed);

}  // namespace radquad
