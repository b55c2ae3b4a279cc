// The links on which the exact gold's error estimate is held to a much tighter gold
// (gold_honesty_test.cpp): partially occluded links of four kinds where an outer cubature can
// misjudge its own error:
//  - slats: the study's grille of thin parallel strips (experiments/scenarios/scenario.h);
//  - crossed slats: the same grille crossed by a second set (many shadow edges, many
//    three-edge events), of at most 8 slats a set (the generator draws 5 to 15), so that truths
//    a thousand times tighter than the golds fit the test's time;
//  - small far source: a source a few hundredths to a tenth of the receiver's size, two to six
//    receiver sizes away, behind one blocker: the shadow's penumbra on the receiver is narrow, so
//    the inner integral is nearly a step, which a cubature's embedded rules can agree on while
//    both are wrong;
//  - overlapping blockers: the study's 2 to 6 blockers, kept where two shadows overlap as seen
//    from some receiver point (their union changes shape across the receiver).
// Each candidate is drawn from deriveSeed(seed, {kind, i}); it is kept when no occluder passes
// through a patch (as the study rejects such candidates) and its visible fraction by a 6^4 Gauss
// product lies strictly inside (0.05, 0.95), as the study's partial links do.
#pragma once

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <numbers>
#include <string>
#include <vector>

#include "experiments/scenarios/random_stream.h"
#include "experiments/scenarios/scenario.h"
#include "kernel/patch_intersection.h"
#include "quadrature/prepared_rule.h"
#include "quadrature/rules/gauss_product.h"
#include "reference/exact_visibility.h"

namespace radquad {

enum class HonestyKind { slats, crossedSlats, smallFarSource, overlappingBlockers };

inline const char* honestyKindName(HonestyKind kind) {
  switch (kind) {
    case HonestyKind::slats: return "slats";
    case HonestyKind::crossedSlats: return "crossed slats";
    case HonestyKind::smallFarSource: return "small far source";
    case HonestyKind::overlappingBlockers: return "overlapping blockers";
  }
  return "?";
}

struct HonestyLink {
  HonestyKind kind = HonestyKind::slats;
  std::uint64_t candidate = 0;
  LinkGeometry geometry;
  std::unique_ptr<OccluderScene> scene;
  Link link() const { return Link{geometry.receiver, geometry.source, scene.get()}; }
};

namespace honesty_detail {

// A centred rectangle of sides w (along e1) and h (along e2).
inline Patch rectangle(const Eigen::Vector3d& centre, const Eigen::Vector3d& e1,
                       const Eigen::Vector3d& e2, double w, double h, const char* name) {
  return Patch::make(centre - 0.5 * w * e1 - 0.5 * h * e2, w * e1, h * e2, name);
}

// A small source 2 to 6 receiver sizes above a receiver of sides 0.5 to 1, tilted by up to 30
// degrees towards it, and one blocker across the beam whose edge falls near the beam's axis.
inline LinkGeometry smallFarSource(ScenarioRandom& random) {
  LinkGeometry link;
  const double a = random.uniform(0.5, 1.0), b = random.uniform(0.5, 1.0);
  link.receiver = rectangle(Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitX(),
                            Eigen::Vector3d::UnitY(), a, b, "receiver");
  const double side = random.logUniform(0.03, 0.15);
  const double height = random.uniform(2.0, 6.0) * std::max(a, b);
  const Eigen::Vector3d centre(random.uniform(-0.3, 0.3), random.uniform(-0.3, 0.3), height);
  // The source faces down (-z), tilted about a random horizontal axis.
  const double spin = random.uniform(0.0, std::numbers::pi);
  const Eigen::Vector3d axis(std::cos(spin), std::sin(spin), 0.0);
  const Eigen::Matrix3d tilt =
      Eigen::AngleAxisd(random.uniform(0.0, 30.0) * std::numbers::pi / 180.0, axis).toRotationMatrix();
  const Eigen::Vector3d e1 = tilt * Eigen::Vector3d::UnitY();
  const Eigen::Vector3d e2 = tilt * Eigen::Vector3d::UnitX();  // e1 x e2 = -z before the tilt
  link.source = rectangle(centre, e1, e2, side, side * random.uniform(0.5, 1.0), "source");
  // The blocker: a large rectangle at a fraction of the height, its edge near the axis.
  const double along = random.uniform(0.15, 0.7);
  const double turn = random.uniform(0.0, std::numbers::pi);
  const Eigen::Vector3d u(std::cos(turn), std::sin(turn), 0.0), v(-std::sin(turn), std::cos(turn), 0.0);
  const double width = random.uniform(0.5, 1.5) * std::max(a, b);
  const double offset = random.uniform(-0.25, 0.25) * std::max(a, b);
  const Eigen::Vector3d middle = along * centre + (offset + 0.5 * width) * u;
  const Eigen::Matrix3d lean =
      Eigen::AngleAxisd(random.uniform(-0.3, 0.3), v).toRotationMatrix();
  link.parallelograms.push_back(rectangle(middle, lean * u, lean * v, width, 2.0 * width, "blocker"));
  return link;
}

// Whether two of the slats' directions differ: the grille is crossed.
inline bool crossed(const LinkGeometry& link) {
  for (const Patch& slat : link.parallelograms) {
    if (slat.edgeV.normalized().cross(link.parallelograms.front().edgeV.normalized()).norm() > 0.5) {
      return true;
    }
  }
  return false;
}

// Whether a generated link is of the kind asked for.
inline bool ofKind(const LinkGeometry& link, HonestyKind kind) {
  switch (kind) {
    case HonestyKind::slats: return !crossed(link);
    case HonestyKind::crossedSlats: return crossed(link) && link.parallelograms.size() <= 16;
    default: return true;
  }
}

// Whether two shadows overlap as seen from some point of a 5 x 5 grid on the receiver.
inline bool shadowsOverlap(const Link& link) {
  ExactVisibility visibility(link);
  VisibleRings rings;
  for (int i = 0; i < 5; ++i) {
    for (int j = 0; j < 5; ++j) {
      visibility.visibleRings(link.receiver.pointAt((i + 0.5) / 5, (j + 0.5) / 5), rings);
    }
  }
  return visibility.statistics().unions > 0;
}

}  // namespace honesty_detail

// `perKind` links of each kind, in the order drawn (kinds in the order listed).
inline std::vector<HonestyLink> honestyLinks(std::uint64_t seed, int perKind,
                                             const std::vector<HonestyKind>& kinds = {
                                                 HonestyKind::slats, HonestyKind::crossedSlats,
                                                 HonestyKind::smallFarSource,
                                                 HonestyKind::overlappingBlockers}) {
  const PreparedRule probe(std::make_shared<GaussProductRule>(GaussPointCounts{6, 6, 6, 6}), 0);
  CouplingAccumulator accumulator;
  std::vector<HonestyLink> links;
  for (const HonestyKind kind : kinds) {
    GeometryRanges ranges;
    ranges.occluders = {kind == HonestyKind::overlappingBlockers ? OccluderKind::severalBlockers
                                                                 : OccluderKind::slats};
    int kept = 0;
    for (std::uint64_t i = 0; kept < perKind && i < 100000; ++i) {
      const std::uint64_t candidate = deriveSeed(seed, {std::uint64_t(kind), i});
      HonestyLink drawn;
      drawn.kind = kind;
      drawn.candidate = i;
      if (kind == HonestyKind::smallFarSource) {
        ScenarioRandom random(candidate);
        drawn.geometry = honesty_detail::smallFarSource(random);
      } else {
        drawn.geometry = generateLink(ranges, StudyClass::partial, candidate);
        if (!honesty_detail::ofKind(drawn.geometry, kind)) continue;
      }
      bool crosses = false;
      for (const Patch& occluder : drawn.geometry.parallelograms) {
        const auto corners = occluder.corners();
        const std::vector<Eigen::Vector3d> polygon(corners.begin(), corners.end());
        crosses = crosses || polygonCrossesPatch(polygon, drawn.geometry.receiver) ||
                  polygonCrossesPatch(polygon, drawn.geometry.source);
      }
      if (crosses) continue;
      drawn.scene = drawn.geometry.occluderScene();
      LinkIntegral probed;
      probe.integrate(drawn.link(), 0, accumulator, probed);
      const double visible = probed.visibleFraction();
      if (visible <= 0.05 || visible >= 0.95) continue;
      if (kind == HonestyKind::overlappingBlockers && !honesty_detail::shadowsOverlap(drawn.link())) {
        continue;
      }
      ++kept;
      links.push_back(std::move(drawn));
    }
  }
  return links;
}

}  // namespace radquad
