// Time per link of the paper's reference (`Reference` = Stratified:10, 10,000 samples) at
// basis degree 2, on an unoccluded and on partially occluded links, and the raw Embree
// occlusion rays the occluded links cast, for the ratio (targets: at most 100 us per
// unoccluded link on one core; at most 1.25 times the raw rays on an occluded one).
//
//   build/release/bench/reference_bench --benchmark_min_time=2
//
// Each iteration integrates with a new seed, so the time includes drawing the points;
// referenceDraw times that draw alone.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <memory>
#include <vector>

#include "kernel/occluder_scene.h"
#include "quadrature/prepared_rule.h"
#include "quadrature/registry.h"

namespace radquad {
namespace {

Patch receiverPatch() {
  return Patch::make({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, "receiver");
}
Patch sourcePatch() {
  return Patch::make({0, 1, 1}, {1, 0, 0}, {0, -1, 0}, "source");
}

// One blocker half way, covering about half of the rays.
void addOneBlocker(OccluderScene& scene) {
  scene.addParallelogram(Patch::make({-0.2, -0.2, 0.5}, {0.7, 0, 0}, {0, 1.4, 0}, "blocker"));
}

// Twenty slats across the gap (a blind), covering about half of the rays.
void addSlats(OccluderScene& scene) {
  for (int i = 0; i < 20; ++i) {
    const double x = -0.1 + 0.06 * i;
    scene.addParallelogram(
        Patch::make({x, -0.2, 0.3 + 0.02 * (i % 5)}, {0.03, 0, 0}, {0, 1.4, 0}, "slat"));
  }
}

enum class Occluders { kNone, kOneBlocker, kSlats };

std::unique_ptr<OccluderScene> makeScene(Occluders which) {
  if (which == Occluders::kNone) return nullptr;
  auto scene = std::make_unique<OccluderScene>();
  if (which == Occluders::kOneBlocker) addOneBlocker(*scene);
  if (which == Occluders::kSlats) addSlats(*scene);
  scene->commit();
  return scene;
}

void referencePerLink(benchmark::State& state, Occluders which) {
  const auto scene = makeScene(which);
  const Link link{receiverPatch(), sourcePatch(), scene.get()};
  const PreparedRule prepared(findRule("Reference"), 2);
  CouplingAccumulator accumulator;
  LinkIntegral result;
  std::uint64_t seed = 0;
  for (auto _ : state) {
    prepared.integrate(link, seed++, accumulator, result);
    benchmark::DoNotOptimize(result.coupling.data());
  }
  state.counters["visible_fraction"] = result.visibleFraction();
  state.counters["rays_per_link"] = double(result.raysCast);
  state.counters["evaluations_per_second"] = benchmark::Counter(
      double(result.kernelEvaluations) * double(state.iterations()), benchmark::Counter::kIsRate);
}

// The same rays (the reference's points of one seed, where the unoccluded kernel is
// positive) traced alone, in place with OccluderScene::trace. Tracing marks blocked rays by
// their tfar, so each iteration first sets every tfar back (a pass over 40 KB, about 1% of
// the time, counted with the rays).
void rawRays(benchmark::State& state, Occluders which) {
  const auto scene = makeScene(which);
  const Patch receiver = receiverPatch(), source = sourcePatch();
  const RuleSamples samples = findRule("Reference")->samples(0);
  SegmentBatch segments;
  for (std::size_t k = 0; k < samples.points.size(); ++k) {
    const Eigen::Vector3d x = receiver.pointAt(samples.points.s[k], samples.points.t[k]);
    const Eigen::Vector3d y = source.pointAt(samples.points.u[k], samples.points.v[k]);
    if (unoccludedKernel(receiver, x, source, y) > 0.0) segments.push(x, y - x);
  }
  for (auto _ : state) {
    for (std::size_t p = 0; p < segments.packetCount(); ++p) {
      SegmentPacket& packet = segments.packets()[p];
      for (int lane = 0; lane < 16; ++lane) packet.tfar[lane] = 1.0f - kSegmentEpsilon;
    }
    scene->trace(segments);
    benchmark::DoNotOptimize(segments.packets());
  }
  state.counters["rays_per_link"] = double(segments.size());
  state.counters["rays_per_second"] = benchmark::Counter(
      double(segments.size()) * double(state.iterations()), benchmark::Counter::kIsRate);
}

// Drawing the reference's 10,000 points alone (Philox4x32-10 and the strata, blocks of 256
// as the streamed integration draws them): a cost paid on every link whatever its visibility.
void referenceDraw(benchmark::State& state) {
  const auto rule = findRule("Reference");
  constexpr std::size_t kBlock = 256;
  std::vector<double> s(kBlock), t(kBlock), u(kBlock), v(kBlock);
  std::uint64_t seed = 0;
  std::size_t points = 0;
  for (auto _ : state) {
    const auto stream = rule->pointStream(seed++);
    points = stream->size();
    for (std::size_t first = 0; first < points; first += kBlock) {
      stream->fill(first, std::min(kBlock, points - first), s.data(), t.data(), u.data(),
                   v.data());
      benchmark::DoNotOptimize(s.data());
      benchmark::DoNotOptimize(v.data());
    }
  }
  state.counters["points_per_link"] = double(points);
}

BENCHMARK(referenceDraw)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(referencePerLink, unoccluded, Occluders::kNone)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(referencePerLink, one_blocker, Occluders::kOneBlocker)
    ->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(rawRays, one_blocker, Occluders::kOneBlocker)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(referencePerLink, slats, Occluders::kSlats)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(rawRays, slats, Occluders::kSlats)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace radquad
