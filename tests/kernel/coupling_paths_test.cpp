// The two coupling paths are independent implementations of the same sum: a product rule's
// points, flattened into a 4D list, must give the same coupling through the scattered path
// (the register-tiled contraction for degrees 1..3, a general matrix product above) as
// through the product path, with and without occluders.
#include <gtest/gtest.h>

#include "kernel/coupling.h"
#include "quadrature/registry.h"
#include "tests/kernel/test_links.h"

namespace radquad {
namespace {

LinkSamples flatten(const RuleSamples& samples) {
  LinkSamples flat;
  for (std::size_t i = 0; i < samples.receiver.size(); ++i) {
    for (std::size_t j = 0; j < samples.source.size(); ++j) {
      flat.push(samples.receiver.u[i], samples.receiver.v[i], samples.source.u[j],
                samples.source.v[j], samples.receiver.weight[i] * samples.source.weight[j]);
    }
  }
  return flat;
}

TEST(CouplingPaths, ScatteredEqualsProductOnTheSamePoints) {
  OccluderScene scene;
  scene.addParallelogram(Patch::make({0.3, -1, 0.5}, {0.4, 0, 0}, {0, 3, 0.1}, "slat"));
  scene.commit();
  const Patch receiver = Patch::make({0, 0, 0}, {1.2, 0, 0.1}, {0, 0.8, 0}, "receiver");
  const Patch source = testing::opposedSource(1, 1, 1.1);
  // 5x3 x 4x7 = 420 points: not a multiple of the 8-lane vectors or the 256-point blocks.
  const RuleSamples samples = findRule("Gauss:5x3x4x7")->samples(0);
  const LinkSamples flat = flatten(samples);
  CouplingAccumulator accumulator;
  const OccluderScene* none = nullptr;
  for (const OccluderScene* occluders : {none, static_cast<const OccluderScene*>(&scene)}) {
    const Link link{receiver, source, occluders};
    for (int degree = 0; degree <= 5; ++degree) {
      const WeightedBasisTable receiverBasis = makeWeightedBasisTable(samples.receiver, degree);
      const WeightedBasisTable sourceBasis = makeWeightedBasisTable(samples.source, degree);
      LinkIntegral product, scattered;
      accumulator.product(link, samples.receiver, receiverBasis, samples.source, sourceBasis,
                          product);
      accumulator.scattered(link, flat, degree, scattered);
      ASSERT_EQ(product.coupling.rows(), scattered.coupling.rows());
      const double scale = product.coupling.cwiseAbs().maxCoeff();
      EXPECT_LT((product.coupling - scattered.coupling).cwiseAbs().maxCoeff(), 1e-13 * scale)
          << "degree " << degree << (occluders ? " occluded" : " unoccluded");
      EXPECT_EQ(product.raysBlocked, scattered.raysBlocked) << "degree " << degree;
      EXPECT_EQ(product.kernelEvaluations, scattered.kernelEvaluations);
    }
  }
}

}  // namespace
}  // namespace radquad
