// The product path contracts in the other order when the source has fewer points than the
// receiver (as the adaptive rules choose): it must still equal the scattered path, an
// independent implementation of the same sum, on the same points.
#include <gtest/gtest.h>

#include "kernel/coupling.h"
#include "quadrature/registry.h"
#include "tests/kernel/test_links.h"

namespace radquad {
namespace {

TEST(CouplingSourceLast, ProductWithFewerSourcePointsEqualsScattered) {
  OccluderScene scene;
  scene.addParallelogram(Patch::make({0.3, -1, 0.5}, {0.4, 0, 0}, {0, 3, 0.1}, "slat"));
  scene.commit();
  const Patch receiver = Patch::make({0, 0, 0}, {1.2, 0, 0.1}, {0, 0.8, 0}, "receiver");
  const Patch source = testing::opposedSource(1, 1, 1.1);
  CouplingAccumulator accumulator;
  const OccluderScene* none = nullptr;
  for (const char* name : {"Gauss:4x4x1x1", "Gauss:4x4x2x1", "Gauss:3x3x1x3", "Gauss:2x2x1x1"}) {
    const RuleSamples samples = findRule(name)->samples(0);
    ASSERT_LT(samples.source.size(), samples.receiver.size()) << name;
    LinkSamples flat;
    for (std::size_t i = 0; i < samples.receiver.size(); ++i) {
      for (std::size_t j = 0; j < samples.source.size(); ++j) {
        flat.push(samples.receiver.u[i], samples.receiver.v[i], samples.source.u[j],
                  samples.source.v[j], samples.receiver.weight[i] * samples.source.weight[j]);
      }
    }
    for (const OccluderScene* occluders : {none, static_cast<const OccluderScene*>(&scene)}) {
      const Link link{receiver, source, occluders};
      for (int degree = 0; degree <= 4; ++degree) {
        const WeightedBasisTable receiverBasis = makeWeightedBasisTable(samples.receiver, degree);
        const WeightedBasisTable sourceBasis = makeWeightedBasisTable(samples.source, degree);
        LinkIntegral product, scattered;
        accumulator.product(link, samples.receiver, receiverBasis, samples.source, sourceBasis,
                            product);
        accumulator.scattered(link, flat, degree, scattered);
        const double scale = product.coupling.cwiseAbs().maxCoeff();
        ASSERT_GT(scale, 0.0);
        EXPECT_LT((product.coupling - scattered.coupling).cwiseAbs().maxCoeff(), 1e-13 * scale)
            << name << " degree " << degree << (occluders ? " occluded" : " unoccluded");
      }
    }
  }
}

}  // namespace
}  // namespace radquad
