// Coupling throughput (kernel evaluations per second, one thread):
//  - unoccluded FullGauss at degree 2 (9x9 coupling matrices);
//  - occluded couplings beside raw Embree rtcOccluded16 calls on exactly the same rays,
//    packed the same way (one link's rays per group of packets), so the ratio of the two
//    rates is the share of the time spent outside Embree.
// Run: build/release/bench/coupling_bench --benchmark_counters_tabular=true
#include <benchmark/benchmark.h>
#include <embree3/rtcore.h>

#include "bench/bench_links.h"
#include "kernel/embree_device.h"
#include "quadrature/prepared_rule.h"
#include "quadrature/registry.h"

namespace radquad::bench {
namespace {

constexpr std::size_t kLinkCount = 256;

void runCouplings(benchmark::State& state, const std::string& ruleName, int degree,
                  const OccluderScene* scene) {
  const auto links = makeLinks(kLinkCount, scene);
  const PreparedRule rule(findRule(ruleName), degree);
  CouplingAccumulator accumulator;
  LinkIntegral result;
  std::uint64_t evaluations = 0, rays = 0, blocked = 0;
  for (auto _ : state) {
    for (const Link& link : links) {
      rule.integrate(link, 0, accumulator, result);
      benchmark::DoNotOptimize(result.coupling.data());
      evaluations += result.kernelEvaluations;
      rays += result.raysCast;
      blocked += result.raysBlocked;
    }
  }
  state.counters["evals_per_s"] =
      benchmark::Counter(double(evaluations), benchmark::Counter::kIsRate);
  if (scene) {
    state.counters["rays_per_s"] = benchmark::Counter(double(rays), benchmark::Counter::kIsRate);
    state.counters["blocked_share"] = double(blocked) / double(rays);
  }
}

void BM_UnoccludedFullGaussDegree2(benchmark::State& state) {
  runCouplings(state, "FullGauss", 2, nullptr);
}
BENCHMARK(BM_UnoccludedFullGaussDegree2);

void BM_UnoccludedFullGaussDegree0(benchmark::State& state) {
  runCouplings(state, "FullGauss", 0, nullptr);
}
BENCHMARK(BM_UnoccludedFullGaussDegree0);

// Arguments: blockers per side of the grid (1: one blocker, 10: 50 blockers), basis degree.
void BM_OccludedFullGauss(benchmark::State& state) {
  const auto scene = makeBlockerScene(int(state.range(0)));
  runCouplings(state, "FullGauss", int(state.range(1)), scene.get());
}
BENCHMARK(BM_OccludedFullGauss)->Args({1, 0})->Args({1, 2})->Args({10, 0})->Args({10, 2});

// The rays BM_OccludedFullGauss casts, traced directly: the receiver's and the source's
// FullGauss points joined pair by pair, 81 rays per link packed into packets of 16.
void BM_RawEmbreeOcclusion(benchmark::State& state) {
  const auto scene = makeBlockerScene(int(state.range(0)));
  const auto links = makeLinks(kLinkCount, scene.get());
  const RuleSamples samples = findRule("FullGauss")->samples(0);
  // One batch per link, as the coupling builds them; traced below with plain rtcOccluded16
  // calls (valid masks built per call, as a caller of the raw API would).
  std::vector<SegmentBatch> batches(links.size());
  for (std::size_t l = 0; l < links.size(); ++l) {
    const Link& link = links[l];
    for (std::size_t i = 0; i < samples.receiver.size(); ++i) {
      for (std::size_t j = 0; j < samples.source.size(); ++j) {
        const Eigen::Vector3d x =
            link.receiver.pointAt(samples.receiver.u[i], samples.receiver.v[i]);
        const Eigen::Vector3d y = link.source.pointAt(samples.source.u[j], samples.source.v[j]);
        batches[l].push(x, y - x);
      }
    }
  }
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
  std::uint64_t rays = 0;
  std::vector<SegmentBatch> work = batches;
  for (auto _ : state) {
    state.PauseTiming();
    work = batches;  // occlusion overwrites tfar
    state.ResumeTiming();
    for (SegmentBatch& batch : work) {
      for (std::size_t p = 0; p < batch.packetCount(); ++p) {
        alignas(64) int valid[16];
        for (std::size_t lane = 0; lane < 16; ++lane) {
          valid[lane] = p * 16 + lane < batch.size() ? -1 : 0;
        }
        rtcOccluded16(valid, scene->handle(), &context, &embreePackets(batch)[p]);
      }
      rays += batch.size();
    }
    benchmark::DoNotOptimize(work.data());
  }
  state.counters["rays_per_s"] = benchmark::Counter(double(rays), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_RawEmbreeOcclusion)->Arg(1)->Arg(10);

}  // namespace
}  // namespace radquad::bench

BENCHMARK_MAIN();
