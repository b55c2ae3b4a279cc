// A gold that cannot vouch for its error: a scene-derived link whose gold does not converge is
// refused and replaced by the next candidate of its class, and the refusals are counted; a
// generated link keeps its unconverged gold (the table counts it, and the run fails).
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <vector>

#include "experiments/study/scene_links.h"
#include "experiments/study/study_runner.h"
#include "reference/gold_reference.h"

namespace radquad {
namespace {

// Figure 2's partial links (degree 2) of a coarse cornell solve, the exact gold on each to 1e-6
// of K's largest entry within `budget` receiver points.
StudyConfig refusalConfig(int partial, std::size_t budget) {
  StudyConfig config = parseStudyConfig(
      nlohmann::json::parse(R"({"figure": "fig2", "seed": 5, "classes": {"partial": 1},
                              "rules": ["FullGauss"], "reference": {"replicates": 3},
                              "gold": {"method": "exact", "exact_tolerance": 1e-6},
                              "links": {"scene": "cornell", "degree": 0, "bf_eps": 0.5}})"),
      "refusal");
  config.classes = {{StudyClass::partial, partial}};
  config.gold.maxEvaluations = budget;
  return config;
}

std::vector<std::uint64_t> candidatesOf(const ClassRun& run) {
  std::vector<std::uint64_t> out;
  for (const LinkRecord& link : run.links) out.push_back(link.candidate);
  return out;
}

TEST(GoldRefusal, AnUnconvergedSceneGoldIsRefusedReplacedAndCounted) {
  StudyOptions options;
  options.gold = true;
  // A budget the exact gold at 1e-6 exceeds on some of these links and not on others.
  const StudyConfig tight = refusalConfig(6, 1500);
  const StudyRun run = runStudy(tight, options);
  const ClassRun& partial = run.classes.front();
  ASSERT_EQ(partial.links.size(), 6u);
  ASSERT_GT(partial.refusedGoldCandidates.size(), 0u);
  for (const LinkRecord& link : partial.links) EXPECT_TRUE(link.goldConverged);
  // Every candidate of the class's own class was either scored or refused.
  EXPECT_EQ(partial.candidatesByOwnClass.at("partial"),
            partial.links.size() + partial.refusedGoldCandidates.size());
  // The refused candidates' golds, computed on their own, do not converge in that budget:
  // the refusal is the gold's own verdict.
  const SceneLinkPool pool(*tight.sceneLinks, tight.seed);
  for (const std::uint64_t k : partial.refusedGoldCandidates) {
    const BuiltLink built = pool.geometry(pool.entry(std::size_t(k))).build();
    EXPECT_FALSE(goldReference(built.link, tight.degree(), 0, tight.gold).converged) << "candidate " << k;
  }
  // With a budget a thousand times larger, the qualifying candidates the tight run examined
  // (scored or refused) come first again, in candidate order: a refused link's place goes to
  // the next candidate of its class. A larger budget refuses no candidate the smaller one
  // scored (some golds never converge: a rounding floor the estimate cannot pass, so the
  // larger run may refuse a few of the same and take the next candidates in their place).
  std::vector<std::uint64_t> examined = candidatesOf(partial);
  examined.insert(examined.end(), partial.refusedGoldCandidates.begin(),
                  partial.refusedGoldCandidates.end());
  std::sort(examined.begin(), examined.end());
  const StudyConfig generous = refusalConfig(int(examined.size()), 1500000);
  const StudyRun all = runStudy(generous, options);
  const ClassRun& wide = all.classes.front();
  for (const std::uint64_t k : wide.refusedGoldCandidates) {
    EXPECT_TRUE(std::find(partial.refusedGoldCandidates.begin(), partial.refusedGoldCandidates.end(),
                          k) != partial.refusedGoldCandidates.end())
        << "candidate " << k << " refused with the larger budget only";
  }
  EXPECT_LT(wide.refusedGoldCandidates.size(), partial.refusedGoldCandidates.size());
  std::vector<std::uint64_t> widened = candidatesOf(wide);
  widened.insert(widened.end(), wide.refusedGoldCandidates.begin(), wide.refusedGoldCandidates.end());
  std::sort(widened.begin(), widened.end());
  ASSERT_GE(widened.size(), examined.size());
  EXPECT_EQ(std::vector<std::uint64_t>(widened.begin(), widened.begin() + std::ptrdiff_t(examined.size())),
            examined);
  // The table reports the count and the candidates, and no unconverged gold.
  const nlohmann::json table = studyTable(tight, options, run);
  const nlohmann::json& counts = table["classes"]["partial"]["candidates"];
  EXPECT_EQ(counts["refused_unconverged_gold"].get<std::size_t>(),
            partial.refusedGoldCandidates.size());
  EXPECT_EQ(counts["refused_gold_candidates"].get<std::vector<std::uint64_t>>(),
            partial.refusedGoldCandidates);
  EXPECT_EQ(table["gold"]["unconverged_links"].get<int>(), 0);
  // The same suite on one thread.
  tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
  EXPECT_EQ(studyTable(tight, options, runStudy(tight, options)).dump(), table.dump());
}

TEST(GoldRefusal, AGeneratedLinksUnconvergedGoldStaysAndIsCounted) {
  // A generated link cannot be replaced without changing the suite's distribution: it keeps
  // its gold, the table counts it (gold.unconverged_links) and the commands exit 3.
  StudyConfig config = parseStudyConfig(
      nlohmann::json::parse(R"({"figure": "fig1", "seed": 11, "classes": {"partial": 3},
                              "rules": ["FullGauss"], "reference": {"replicates": 3},
                              "gold": {"method": "exact", "exact_tolerance": 1e-9}})"),
      "generated");
  config.gold.maxEvaluations = 1000;
  StudyOptions options;
  options.gold = true;
  const StudyRun run = runStudy(config, options);
  const ClassRun& partial = run.classes.front();
  ASSERT_EQ(partial.links.size(), 3u);
  EXPECT_TRUE(partial.refusedGoldCandidates.empty());
  int unconverged = 0;
  for (const LinkRecord& link : partial.links) unconverged += link.goldConverged ? 0 : 1;
  EXPECT_GT(unconverged, 0);
  EXPECT_EQ(studyTable(config, options, run)["gold"]["unconverged_links"].get<int>(), unconverged);
}

}  // namespace
}  // namespace radquad
