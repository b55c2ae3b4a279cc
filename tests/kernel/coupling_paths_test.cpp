// The two coupling paths are independent implementations of the same sum: a product rule's
// points, flattened into a 4D list, must give the same coupling through the scattered path
// (the register-tiled contraction for degrees 1..3, a general matrix product above) as
// through the product path (which contracts source-last when the source has fewer points
// than the receiver, as the adaptive rules choose), with and without occluders, at every
// basis degree (each has its own compiled contraction).
#include <gtest/gtest.h>

#include "quadrature/rule.h"
#include "kernel/coupling.h"
#include "kernel/legendre_basis.h"
#include "quadrature/registry.h"
#include "tests/kernel/test_links.h"

namespace radquad {
namespace {


TEST(CouplingPaths, ScatteredEqualsProductOnTheSamePoints) {
  OccluderScene scene;
  scene.addParallelogram(Patch::make({0.3, -1, 0.5}, {0.4, 0, 0}, {0, 3, 0.1}, "slat"));
  scene.commit();
  const Patch receiver = Patch::make({0, 0, 0}, {1.2, 0, 0.1}, {0, 0.8, 0}, "receiver");
  const Patch source = testing::opposedSource(1, 1, 1.1);
  CouplingAccumulator accumulator;
  const OccluderScene* none = nullptr;
  // 5x3 x 4x7 = 420 points: not a multiple of the 8-lane vectors or the 256-point blocks;
  // the others have fewer source than receiver points.
  for (const char* name :
       {"Gauss:5x3x4x7", "Gauss:4x4x1x1", "Gauss:4x4x2x1", "Gauss:3x3x1x3", "Gauss:2x2x1x1"}) {
    const RuleSamples samples = findRule(name)->samples(0);
    const LinkSamples flat = flattenedPoints(samples);
    for (const OccluderScene* occluders : {none, static_cast<const OccluderScene*>(&scene)}) {
      const Link link{receiver, source, occluders};
      for (int degree = 0; degree <= kMaxBasisDegree; ++degree) {
        const WeightedBasisTable receiverBasis = makeWeightedBasisTable(samples.receiver, degree);
        const WeightedBasisTable sourceBasis = makeWeightedBasisTable(samples.source, degree);
        LinkIntegral product, scattered;
        accumulator.product(link, samples.receiver, receiverBasis, samples.source, sourceBasis,
                            product);
        accumulator.scattered(link, flat, degree, scattered);
        ASSERT_EQ(product.coupling.rows(), scattered.coupling.rows());
        const double scale = product.coupling.cwiseAbs().maxCoeff();
        ASSERT_GT(scale, 0.0) << name;
        EXPECT_LT((product.coupling - scattered.coupling).cwiseAbs().maxCoeff(), 1e-13 * scale)
            << name << " degree " << degree << (occluders ? " occluded" : " unoccluded");
        EXPECT_EQ(product.raysBlocked, scattered.raysBlocked) << name << " degree " << degree;
        EXPECT_EQ(product.kernelEvaluations, scattered.kernelEvaluations) << name;
      }
    }
  }
}

// The streamed path (fused per block, the points drawn block by block) against the scattered
// path on the rule's stored samples of the same seed: the same sum in another order, the same
// rays. Stratified:5 has 625 points (not a multiple of 8 or 256); the tilted source reaches
// behind the receiver's plane, so some kernels are zero and are left out of the rays.
TEST(CouplingPaths, StreamedEqualsScatteredOnTheSamePoints) {
  OccluderScene opposedBlocker, tiltedBlocker;
  opposedBlocker.addParallelogram(Patch::make({0.3, -1, 0.5}, {0.4, 0, 0}, {0, 3, 0.1}, "slat"));
  opposedBlocker.commit();
  tiltedBlocker.addParallelogram(Patch::make({0.2, 1.2, -0.2}, {0.4, 0, 0}, {0, 0, 0.6}, "wall"));
  tiltedBlocker.commit();
  const Patch receiver = Patch::make({0, 0, 0}, {1.2, 0, 0.1}, {0, 0.8, 0}, "receiver");
  const Patch opposed = testing::opposedSource(1, 1, 1.1);
  const Patch tilted = Patch::make({0, 1.5, -0.5}, {1, 0, 0}, {0, 0, 1.5}, "tilted source");
  const std::vector<Link> links = {{receiver, opposed, nullptr},
                                   {receiver, opposed, &opposedBlocker},
                                   {receiver, tilted, nullptr},
                                   {receiver, tilted, &tiltedBlocker}};
  CouplingAccumulator accumulator;
  for (const char* name : {"Stratified", "Stratified:5", "Reference"}) {
    const auto rule = findRule(name);
    for (std::uint64_t seed : {0ull, 977ull}) {
      const RuleSamples samples = rule->samples(seed);
      const auto stream = rule->pointStream(seed);
      ASSERT_TRUE(stream) << name;
      ASSERT_EQ(stream->size(), samples.size()) << name;
      for (std::size_t l = 0; l < links.size(); ++l) {
        for (int degree = 0; degree <= 4; ++degree) {
          LinkIntegral streamed, scattered;
          accumulator.streamed(links[l], *stream, degree, streamed);
          accumulator.scattered(links[l], samples.points, degree, scattered);
          const double scale = scattered.coupling.cwiseAbs().maxCoeff();
          ASSERT_GT(scale, 0.0) << name << " link " << l;
          EXPECT_LT((streamed.coupling - scattered.coupling).cwiseAbs().maxCoeff(), 1e-12 * scale)
              << name << " seed " << seed << " link " << l << " degree " << degree;
          EXPECT_NEAR(streamed.formFactor, scattered.formFactor, 1e-12 * scattered.formFactor);
          EXPECT_EQ(streamed.raysCast, scattered.raysCast) << name << " link " << l;
          EXPECT_EQ(streamed.raysBlocked, scattered.raysBlocked) << name << " link " << l;
          EXPECT_EQ(streamed.kernelEvaluations, scattered.kernelEvaluations) << name;
        }
      }
    }
  }
  // The tilted link really has zero kernels (fewer rays than points) and blocked rays.
  LinkIntegral check;
  accumulator.streamed(links[3], *findRule("Reference")->pointStream(0), 0, check);
  EXPECT_LT(check.raysCast, check.kernelEvaluations);
  EXPECT_GT(check.raysBlocked, 0u);
}

}  // namespace
}  // namespace radquad
