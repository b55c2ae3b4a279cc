// The study runner: output independent of the thread count, qualification of partial links,
// and the reference's standard error against the reference library's own estimator.
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include "experiments/scenarios/random_stream.h"
#include "experiments/study/reference_estimate.h"
#include "experiments/study/study_runner.h"
#include "reference/stratified_reference.h"

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
  EXPECT_EQ(partial.generated,
            partial.links.size() + partial.rejectedMostlyBlocked + partial.rejectedMostlyVisible);
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

TEST(StudyRunner, ReferenceStandardErrorAgreesWithTheReferenceLibrary) {
  // The runner's single-pass (Welford) estimator against stratifiedReference's two-pass one.
  const GeometryRanges ranges;
  for (const StudyClass linkClass : {StudyClass::unoccluded, StudyClass::partial}) {
    const GeneratedLink generated = generateLink(ranges, linkClass, 5);
    const auto scene = generated.buildScene();
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

}  // namespace
}  // namespace radquad
