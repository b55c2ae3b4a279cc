// The study runner: output independent of the thread count, qualification of partial links,
// and the reference's standard error against the reference library's own estimator.
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include "experiments/scenarios/random_stream.h"
#include "experiments/study/reference_estimate.h"
#include "experiments/study/study_metrics.h"
#include "experiments/study/study_runner.h"
#include "reference/stratified_reference.h"
#include "experiments/json_input.h"
#include "experiments/scene_input.h"
#include "quadrature/prepared_rule.h"
#include "quadrature/registry.h"
#include "experiments/study/scene_links.h"
#include "kernel/input_error.h"

#include <cmath>
#include <sstream>

namespace radquad {
namespace {

StudyConfig tinyConfig(int unoccluded, int partial) {
  StudyConfig config = parseStudyConfig(
      nlohmann::json::parse(R"({"figure": "fig2", "seed": 11, "classes": {"partial": 1},
                              "rules": ["FullGauss", "Stroud65", "NRook", "Stratified"],
                              "trials": 3, "reference": {"replicates": 3}})"),
      "tiny");
  config.classes = {{StudyClass::unoccluded, unoccluded}, {StudyClass::partial, partial}};
  return config;
}

TEST(StudyRunner, TheTableIsTheSameWhateverTheThreadCount) {
  const StudyConfig config = tinyConfig(6, 10);
  std::string tables[2];
  for (const int threads : {1, 2}) {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, std::size_t(threads));
    const StudyRun run = runStudy(config, StudyOptions{});
    tables[threads - 1] = studyTable(config, StudyOptions{}, run).dump();
  }
  EXPECT_EQ(tables[0], tables[1]);
}

TEST(StudyRunner, PartialLinksQualifyByTheReferenceVisibleFraction) {
  const StudyConfig config = tinyConfig(3, 12);
  const StudyRun run = runStudy(config, StudyOptions{});
  ASSERT_EQ(run.classes.size(), 2u);
  const ClassRun& unoccluded = run.classes[0];
  EXPECT_EQ(unoccluded.links.size(), 3u);
  EXPECT_EQ(unoccluded.generated, 3u);  // every unoccluded candidate qualifies
  for (const LinkRecord& link : unoccluded.links) EXPECT_EQ(link.visibleFraction, 1.0);
  const ClassRun& partial = run.classes[1];
  ASSERT_EQ(partial.links.size(), 12u);
  EXPECT_EQ(partial.generated, partial.links.size() + partial.rejectedMostlyBlocked +
                                   partial.rejectedMostlyVisible +
                                   partial.rejectedOccluderCrossesPatch);
  for (const LinkRecord& link : partial.links) {
    EXPECT_GT(link.visibleFraction, 0.05);
    EXPECT_LT(link.visibleFraction, 0.95);
    EXPECT_EQ(link.relativeError.size(), 4u);
    EXPECT_EQ(link.l1Bound[0].size(), 9u);
  }
  // The suite is the first N qualifying candidates: a smaller suite is a prefix of it.
  const StudyRun smaller = runStudy(tinyConfig(1, 5), StudyOptions{});
  for (std::size_t k = 0; k < 5; ++k) {
    EXPECT_EQ(smaller.classes[1].links[k].candidate, partial.links[k].candidate);
    EXPECT_EQ(smaller.classes[1].links[k].relativeError, partial.links[k].relativeError);
  }
}

Eigen::MatrixXd matrixFromJson(const nlohmann::json& rows) {
  Eigen::MatrixXd out(rows.size(), rows[0].size());
  for (std::size_t a = 0; a < rows.size(); ++a) {
    for (std::size_t b = 0; b < rows[a].size(); ++b) out(Eigen::Index(a), Eigen::Index(b)) = rows[a][b];
  }
  return out;
}

// The per-link table (--links-out): one line per scored link; each line's geometry, read back
// through the link-file loader (a different path from the generator's), integrates to the
// coupling the line records for every deterministic rule, and the table's relative errors
// follow from the line's couplings.
TEST(StudyRunner, PerLinkLinesReproduceTheirCouplingsFromTheirGeometry) {
  const StudyConfig config = tinyConfig(2, 4);
  StudyOptions options;
  options.keepDetails = true;
  const StudyRun run = runStudy(config, options);
  const std::string text = linkTableLines(config, run);
  std::istringstream lines(text);
  std::string line;
  std::size_t count = 0, triangles = 0, parallelograms = 0;
  while (std::getline(lines, line)) {
    const nlohmann::json entry = nlohmann::json::parse(line);
    const ClassRun& classRun = run.classes[entry["class"] == "unoccluded" ? 0 : 1];
    const std::size_t index =
        count < run.classes[0].links.size() ? count : count - run.classes[0].links.size();
    const LinkRecord& record = classRun.links[index];
    ++count;
    EXPECT_EQ(entry["candidate"], record.candidate);
    const LinkGeometry description = parseLink(
        {{"receiver", entry["receiver"]}, {"source", entry["source"]}, {"occluders", entry["occluders"]}},
        "line " + std::to_string(count));
    triangles += description.triangles.size();
    parallelograms += description.parallelograms.size();
    const BuiltLink built = description.build();
    const Eigen::MatrixXd reference = matrixFromJson(entry["reference"]["coupling"]);
    ASSERT_EQ(entry["rules"].size(), run.rules.size());
    for (std::size_t r = 0; r < run.rules.size(); ++r) {
      const nlohmann::json& rule = entry["rules"][r];
      EXPECT_EQ(rule["name"], run.rules[r].name);
      const Eigen::MatrixXd coupling = matrixFromJson(rule["coupling"]);
      if (run.rules[r].random) {
        EXPECT_EQ(rule["trials"], 3);
        EXPECT_GT(matrixFromJson(rule["standard_deviation"]).maxCoeff(), 0.0);
        continue;
      }
      const PreparedRule prepared(findRule(run.rules[r].name), config.degree());
      const LinkIntegral again = prepared.integrate(built.link);
      EXPECT_LE((again.coupling - coupling).cwiseAbs().maxCoeff(),
                1e-12 * coupling.cwiseAbs().maxCoeff())
          << run.rules[r].name << " on line " << count;
      EXPECT_NEAR(std::abs(coupling(0, 0) - reference(0, 0)) / reference(0, 0),
                  record.relativeError[r], 1e-12);
    }
  }
  EXPECT_EQ(count, 6u);
  EXPECT_GT(triangles + parallelograms, 0u);
}

TEST(StudyRunner, ReferenceStandardErrorAgreesWithTheReferenceLibrary) {
  // The runner's single-pass (Welford) estimator against stratifiedReference's two-pass one.
  const GeometryRanges ranges;
  for (const StudyClass linkClass : {StudyClass::unoccluded, StudyClass::partial}) {
    const GeneratedLink generated = generateLink(ranges, linkClass, 5);
    const auto scene = generated.occluderScene();
    const Link link{generated.receiver, generated.source, scene.get()};
    const ReferenceOptions options{10, 4};
    const ReferenceEstimator estimator(options, 2);
    CouplingAccumulator accumulator;
    LinkIntegral draw;
    estimator.draw(link, 77, accumulator, draw);
    const ReferenceResult mine = estimator.estimate(link, 77, draw, accumulator);
    const ReferenceEstimate theirs = stratifiedReference(link, 2, 77, options);
    EXPECT_TRUE(mine.integral.coupling.isApprox(theirs.integral.coupling, 1e-14));
    EXPECT_TRUE(mine.standardError.isApprox(theirs.couplingStandardError, 1e-9))
        << mine.standardError << "\nvs\n"
        << theirs.couplingStandardError;
  }
}

// The gold-noise check: per class, rule and metric, the gold's own mean error (recomputed here
// from each link's gold error matrix) over the rule's mean error against the gold; the gold
// is better than every rule, and the check holds when the worst share is at most 1%.
TEST(StudyRunner, TheGoldNoiseShareIsTheGoldsOwnErrorOverTheRulesMeanError) {
  StudyConfig config = tinyConfig(2, 3);
  config.gold.exactTolerance = 1e-6;
  StudyOptions options;
  options.gold = true;
  options.keepDetails = true;
  const StudyRun run = runStudy(config, options);
  const nlohmann::json table = studyTable(config, options, run);
  double worst = 0.0;
  for (const ClassRun& classRun : run.classes) {
    const nlohmann::json& rules = table["classes"][studyClassName(classRun.linkClass)]["rules"];
    const double n = double(classRun.links.size());
    double ownRelative = 0.0, ownBound = 0.0, ownFrobenius = 0.0;
    for (const LinkRecord& link : classRun.links) {
      const Eigen::MatrixXd& G = link.detail->gold;
      const Eigen::MatrixXd& E = link.detail->goldError;
      ownRelative += E(0, 0) / G(0, 0) / n;
      ownFrobenius += std::sqrt(E.cwiseAbs2().sum() / G.cwiseAbs2().sum()) / n;
      for (const double b : l1ErrorBound(E, link.detail->receiver.area)) ownBound += b / n;
    }
    for (std::size_t r = 0; r < run.rules.size(); ++r) {
      double ruleRelative = 0.0, ruleBound = 0.0, ruleFrobenius = 0.0;
      for (const LinkRecord& link : classRun.links) {
        ruleRelative += link.relativeErrorVsGold[r] / n;
        ruleFrobenius += link.frobeniusErrorVsGold[r] / n;
        for (const double b : link.l1BoundVsGold[r]) ruleBound += b / n;
      }
      const nlohmann::json& share = rules[r]["gold_noise_share"];
      EXPECT_NEAR(share["relative_error"].get<double>(), ownRelative / ruleRelative,
                  1e-9 * ownRelative / ruleRelative);
      EXPECT_NEAR(share["l1_error_bound_total"].get<double>(), ownBound / ruleBound,
                  1e-9 * ownBound / ruleBound);
      EXPECT_NEAR(share["relative_frobenius_error"].get<double>(), ownFrobenius / ruleFrobenius,
                  1e-9 * ownFrobenius / ruleFrobenius);
      for (const double value : {ownRelative / ruleRelative, ownBound / ruleBound,
                                 ownFrobenius / ruleFrobenius}) {
        EXPECT_LT(value, 1.0) << run.rules[r].name;
        worst = std::max(worst, value);
      }
    }
  }
  const nlohmann::json& check = table["gold"]["noise_check"];
  EXPECT_NEAR(check["worst"]["share"].get<double>(), worst, 1e-9 * worst);
  EXPECT_EQ(check["holds"].get<bool>(), worst <= 0.01);
}

// Whether a corner of `patch` lies on the plane of `other` (within rounding), or corners lie on
// both sides of it.
bool meetsThePlaneOf(const Patch& patch, const Patch& other) {
  const double scale = std::max(patch.edgeU.norm(), patch.edgeV.norm());
  bool below = false, above = false;
  for (const Eigen::Vector3d& corner : patch.corners()) {
    const double height = other.normal.dot(corner - other.origin);
    if (std::fabs(height) <= 1e-9 * scale) return true;
    (height < 0.0 ? below : above) = true;
  }
  return below && above;
}

StudyConfig sceneConfig(int unoccluded, int partial, int singular = 0) {
  StudyConfig config = parseStudyConfig(
      nlohmann::json::parse(R"({"figure": "fig2", "seed": 5, "classes": {"partial": 1},
                              "rules": ["FullGauss", "Stratified"], "trials": 2,
                              "reference": {"replicates": 3},
                              "links": {"scene": "cornell", "degree": 0, "bf_eps": 0.5}})"),
      "scene");
  config.classes = {{StudyClass::unoccluded, unoccluded}, {StudyClass::partial, partial}};
  if (singular > 0) config.classes.emplace_back(StudyClass::singular, singular);
  return config;
}

TEST(SceneLinks, ASuiteOfASolvesLinksIsTheSameWhateverTheThreadCount) {
  const StudyConfig config = sceneConfig(5, 5, 2);
  std::string tables[2];
  for (const int threads : {1, 2}) {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, std::size_t(threads));
    StudyOptions options;
    options.keepDetails = true;
    const StudyRun run = runStudy(config, options);
    ASSERT_EQ(run.classes.size(), 3u);
    EXPECT_EQ(run.sceneSolverUnoccluded + run.sceneSolverPartial + run.sceneOccludedLinks,
              run.sceneLinks);
    for (const ClassRun& classRun : run.classes) {
      EXPECT_EQ(classRun.links.size(), std::size_t(classRun.wanted));
      // Every candidate drawn is counted under its own class, the class's own as its links.
      std::uint64_t counted = 0;
      for (const auto& [name, count] : classRun.candidatesByOwnClass) counted += count;
      EXPECT_EQ(counted, classRun.generated);
      EXPECT_EQ(classRun.candidatesByOwnClass.at(studyClassName(classRun.linkClass)),
                classRun.links.size() + classRun.refusedGoldCandidates.size());
      for (const LinkRecord& link : classRun.links) {
        EXPECT_EQ(link.occluderKind, OccluderKind::scene);
        // A link is unoccluded when no occluder meets its shaft (exact, by clipping): the
        // reference's Embree rays, an independent visibility test, are then never blocked.
        // A partial link's rays see between 5% and 95% of the pairs.
        if (classRun.linkClass == StudyClass::unoccluded) {
          EXPECT_EQ(link.visibleFraction, 1.0);
        } else if (classRun.linkClass == StudyClass::partial) {
          EXPECT_GT(link.visibleFraction, 0.05);
          EXPECT_LT(link.visibleFraction, 0.95);
        } else {
          // Singular: the patches touch or one crosses the other's plane, so a corner of one
          // lies on the other's plane or corners lie on both sides of it.
          ASSERT_TRUE(link.detail);
          EXPECT_TRUE(meetsThePlaneOf(link.detail->source, link.detail->receiver) ||
                      meetsThePlaneOf(link.detail->receiver, link.detail->source));
        }
      }
    }
    tables[threads - 1] = studyTable(config, StudyOptions{}, run).dump();
  }
  EXPECT_EQ(tables[0], tables[1]);
}

TEST(SceneLinks, ThePoolHoldsTheSolvesFinalLinksAsPatchesWithTheRestOfTheSceneAsOccluders) {
  const SceneLinkPool pool(SceneLinkOptions{{"cornell"}, 0, 0.5}, 5);
  const Scene scene = loadScene("cornell");
  EXPECT_EQ(pool.size() + pool.occludedLinks(), pool.totalLinks());
  EXPECT_EQ(pool.solverUnoccludedLinks() + pool.solverPartialLinks(), pool.size());
  ASSERT_GT(pool.solverPartialLinks(), 10u);
  for (std::size_t k = 0; k < 10; ++k) {
    const SceneLinkEntry entry = pool.entry(k);
    EXPECT_NE(entry.receiverPatch, entry.sourcePatch);
    // Elements lie inside their patches: same plane, area at most the patch's.
    const Patch& patch = scene.patches[std::size_t(entry.receiverPatch)].patch;
    EXPECT_NEAR(std::fabs(entry.receiver.normal.dot(patch.normal)), 1.0, 1e-12);
    EXPECT_LE(entry.receiver.area, patch.area * (1 + 1e-12));
    const auto occluders = pool.geometry(entry).occluderScene();
    EXPECT_EQ(occluders->primitiveCount(), scene.patches.size() - 2);
  }
}

// Several scenes form one pool: its classes hold every scene's links (the single-scene pools'
// counts add up), and each link's occluders are the other patches of its own scene.
TEST(SceneLinks, APoolOfTwoScenesHoldsBothScenesLinks) {
  const SceneLinkPool cornell(SceneLinkOptions{{"cornell"}, 0, 0.5}, 5);
  const SceneLinkPool slats(SceneLinkOptions{{"slats"}, 0, 0.5}, 5);
  const SceneLinkPool both(SceneLinkOptions{{"cornell", "slats"}, 0, 0.5}, 5);
  EXPECT_EQ(both.size(), cornell.size() + slats.size());
  EXPECT_EQ(both.solverUnoccludedLinks(),
            cornell.solverUnoccludedLinks() + slats.solverUnoccludedLinks());
  EXPECT_EQ(both.totalLinks(), cornell.totalLinks() + slats.totalLinks());
  const std::size_t patches[2] = {loadScene("cornell").patches.size(), loadScene("slats").patches.size()};
  int seen[2] = {0, 0};
  for (std::size_t k = 0; k < both.size(); ++k) {
    const SceneLinkEntry entry = both.entry(k);
    ASSERT_TRUE(entry.scene == 0 || entry.scene == 1);
    ++seen[entry.scene];
    if (k < 20) {
      EXPECT_EQ(both.geometry(entry).occluderScene()->primitiveCount(), patches[entry.scene] - 2);
    }
  }
  EXPECT_GT(seen[0], 0);
  EXPECT_GT(seen[1], 0);
}

TEST(SceneLinks, ConfigsRejectGeometryBesideSceneLinksAndNameBadScenes) {
  const auto parse = [](const char* text) {
    return parseStudyConfig(nlohmann::json::parse(text), "cfg");
  };
  EXPECT_THROW(parse(R"({"figure": "fig1", "seed": 1, "classes": {"partial": 1},
                         "rules": ["FullGauss"], "geometry": {},
                         "links": {"scene": "cornell"}})"),
               InputError);
  EXPECT_THROW(parse(R"({"figure": "fig1", "seed": 1, "classes": {"partial": 1},
                         "rules": ["FullGauss"], "links": {"degree": 2}})"),
               InputError);
  EXPECT_THROW(parse(R"({"figure": "fig1", "seed": 1, "classes": {"partial": 1},
                         "rules": ["FullGauss"], "links": {"scene": []}})"),
               InputError);
  EXPECT_THROW(parse(R"({"figure": "fig1", "seed": 1, "classes": {"partial": 1},
                         "rules": ["FullGauss"], "links": {"scene": ["cornell", 3]}})"),
               InputError);
  // A list round-trips as a list, one scene as a string.
  EXPECT_EQ(studyConfigToJson(parse(R"({"figure": "fig1", "seed": 1, "classes": {"partial": 1},
                         "rules": ["FullGauss"], "links": {"scene": ["cornell", "slats"]}})"))["links"]["scene"],
            nlohmann::json::array({"cornell", "slats"}));
  EXPECT_THROW(parse(R"({"figure": "fig1", "seed": 1, "classes": {"partial": 1},
                         "rules": ["FullGauss"], "links": {"scene": "cornell", "degree": 4}})"),
               InputError);
  // Singular links are scene-derived only.
  EXPECT_THROW(parse(R"({"figure": "fig2", "seed": 1, "classes": {"singular": 1},
                         "rules": ["FullGauss"]})"),
               InputError);
  StudyConfig config = parse(R"({"figure": "fig1", "seed": 1, "classes": {"partial": 1},
                                 "rules": ["FullGauss"], "links": {"scene": "no_such_scene"}})");
  EXPECT_THROW(runStudy(config, StudyOptions{}), InputError);
}

}  // namespace
}  // namespace radquad
