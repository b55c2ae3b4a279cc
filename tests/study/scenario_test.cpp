// Scenario generation: determinism, the ranges of the config, and the geometric promises of
// experiments/scenarios/scenario.h (patches face each other and never touch).
#include <gtest/gtest.h>

#include <algorithm>
#include <set>

#include "experiments/scenarios/random_stream.h"
#include "experiments/scenarios/scenario.h"
#include "experiments/study/study_config.h"
#include "kernel/input_error.h"

namespace radquad {
namespace {

// Every corner of `patch` strictly in front of `other`'s plane.
bool whollyInFront(const Patch& patch, const Patch& other) {
  for (const double u : {0.0, 1.0}) {
    for (const double v : {0.0, 1.0}) {
      if (other.normal.dot(patch.pointAt(u, v) - other.origin) <= 0.0) return false;
    }
  }
  return true;
}

TEST(Scenario, TheSameSeedGivesTheSameLink) {
  const GeometryRanges ranges;
  for (std::uint64_t seed = 0; seed < 20; ++seed) {
    const GeneratedLink a = generateLink(ranges, StudyClass::partial, seed);
    const GeneratedLink b = generateLink(ranges, StudyClass::partial, seed);
    EXPECT_EQ(a.receiver.origin, b.receiver.origin);
    EXPECT_EQ(a.source.edgeU, b.source.edgeU);
    EXPECT_EQ(a.parallelograms.size(), b.parallelograms.size());
    EXPECT_EQ(a.vertices, b.vertices);
  }
  EXPECT_NE(generateLink(ranges, StudyClass::partial, 1).source.origin,
            generateLink(ranges, StudyClass::partial, 2).source.origin);
}

TEST(Scenario, LinksCoverTheConfiguredRanges) {
  const GeometryRanges ranges;
  std::set<Orientation> orientations;
  std::set<OccluderKind> kinds;
  for (std::uint64_t seed = 0; seed < 400; ++seed) {
    const GeneratedLink link = generateLink(ranges, StudyClass::partial, deriveSeed(99, {seed}));
    orientations.insert(link.orientation);
    kinds.insert(link.occluderKind);
    for (const Patch* patch : {&link.receiver, &link.source}) {
      for (const double side : {patch->edgeU.norm(), patch->edgeV.norm()}) {
        EXPECT_GE(side, ranges.minSide - 1e-12);
        EXPECT_LE(side, ranges.maxSide + 1e-12);
      }
    }
    EXPECT_GE(link.distanceFactor, ranges.minDistanceFactor);
    EXPECT_LE(link.distanceFactor, ranges.maxDistanceFactor);
    EXPECT_TRUE(whollyInFront(link.source, link.receiver)) << "seed " << seed;
    EXPECT_TRUE(whollyInFront(link.receiver, link.source)) << "seed " << seed;
    EXPECT_TRUE(link.hasOccluders()) << "seed " << seed;
    if (link.occluderKind == OccluderKind::soup) {
      EXPECT_EQ(link.triangles.size(), 1000u);
    }
    if (link.orientation == Orientation::perpendicular) {
      EXPECT_NEAR(link.receiver.normal.dot(link.source.normal), 0.0, 1e-12);
    }
    if (link.orientation == Orientation::parallel) {
      EXPECT_NEAR(link.receiver.normal.dot(link.source.normal), -1.0, 1e-12);
    }
    if (link.orientation == Orientation::tilted) {
      // Each patch tilted by at most 75 degrees: the normals differ from opposed by at most 150.
      EXPECT_LE(std::acos(-link.receiver.normal.dot(link.source.normal)),
                150.0 * M_PI / 180.0 + 1e-9);
    }
  }
  EXPECT_EQ(orientations.size(), 3u);
  EXPECT_EQ(kinds.size(), 4u);
}

TEST(Scenario, UnoccludedLinksHaveNoOccluders) {
  const GeometryRanges ranges;
  for (std::uint64_t seed = 0; seed < 50; ++seed) {
    const GeneratedLink link = generateLink(ranges, StudyClass::unoccluded, seed);
    EXPECT_FALSE(link.hasOccluders());
    EXPECT_EQ(link.occluderScene(), nullptr);
  }
}

TEST(Scenario, ConfigRejectsUnknownKeysAndBadValues) {
  const auto base = nlohmann::json::parse(
      R"({"figure": "fig2", "seed": 3, "classes": {"partial": 5}, "rules": ["FullGauss"]})");
  EXPECT_NO_THROW(parseStudyConfig(base, "config"));
  const auto expectError = [&](const char* key, const nlohmann::json& value, const char* message) {
    nlohmann::json config = base;
    config[key] = value;
    try {
      parseStudyConfig(config, "config");
      ADD_FAILURE() << "accepted " << config.dump();
    } catch (const InputError& error) {
      EXPECT_NE(std::string(error.what()).find(message), std::string::npos) << error.what();
    }
  };
  expectError("colour", 1, "unknown key 'colour'");
  expectError("geometry", {{"max_sides", 1.0}}, "unknown key 'max_sides'");
  expectError("geometry", {{"occluders", {"soup", "cloud"}}}, "occluders[1]: unknown name");
  expectError("rules", {"FullGauss", "NoSuchRule"}, "rules[1]: unknown rule 'NoSuchRule'");
  expectError("classes", {{"partial", 0}}, "classes: partial");
  expectError("figure", "fig3", "figure");
  expectError("reference", {{"replicates", 1}}, "replicates");
  expectError("visible_fraction", {0.9, 0.1}, "visible_fraction");
  nlohmann::json fig1 = base;
  fig1["figure"] = "fig1";
  fig1["classes"] = {{"unoccluded", 5}};
  EXPECT_THROW(parseStudyConfig(fig1, "config"), InputError);
}

}  // namespace
}  // namespace radquad
