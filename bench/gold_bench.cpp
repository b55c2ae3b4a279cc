// Time per link of the gold references on the study's partial links (the Figure 1 suite's
// generator, experiments/scenarios/scenario.h, default geometry): the exact-visibility gold
// (reference/exact_gold.h) beside the dense stratified gold of the study configs (16^4
// strata, 8 replicates = 524,288 samples), at degree 0 and 2, per occluder kind.
//
//   build/release/bench/gold_bench --benchmark_min_time=0.05   (one thread; about 10 minutes)
//
// Each iteration integrates the same 6 links of one kind (the first 6 candidates of seed 1
// whose visible fraction, by a 6^4 Gauss rule, lies in (0.05, 0.95):
// experiments/scenarios/probed_links.h), or 24 for the `wide_` rows (the study's tolerance
// only); the time per link is the iteration time / the links. Counters: receiver_points (exact), max_relative_error (the largest
// reported error over the largest |K| entry; for dense stratified its standard error),
// by_critical_lines and by_jump_lines (the shares of links whose outer integral took the
// critical lines or the jump lines; the rest took Genz-Malik, exact_gold.h), unoccluded_apart
// (the share of links whose unoccluded part was integrated apart: degree >= 1 with the
// receiver in front of the source's plane, exact_gold.h). The `_genz_malik` variants force
// Genz-Malik on every link, for comparison.
// The soup's exact gold is capped at 20,000 receiver points (it does not converge there).
// unionClipper / unionBoostGeometry / unionOutline: the shadows' union by Clipper (the exact
// gold's fallback), by Boost.Geometry, and as the outline's pieces (what the exact gold takes),
// on the same overlapping quadrilaterals (counter `area` checks they agree).
#include <benchmark/benchmark.h>
#include <tbb/global_control.h>
#include <polyclipping/clipper.hpp>

#include <boost/geometry.hpp>
#include <boost/geometry/geometries/point_xy.hpp>
#include <boost/geometry/geometries/polygon.hpp>
#include <cmath>
#include <random>

#include <algorithm>
#include <cstdint>
#include <memory>
#include <vector>

#include "experiments/scenarios/probed_links.h"
#include "reference/exact_gold.h"
#include "reference/exact_visibility.h"
#include "reference/gold_reference.h"

namespace radquad {
namespace {

constexpr int kLinksPerKind = 6;

// The links of one kind and their Link views (probed_links.h, seed 1).
struct KindLinks {
  std::vector<ProbedLink> drawn;
  std::vector<Link> links;
};

KindLinks partialLinks(OccluderKind kind, int count = kLinksPerKind) {
  KindLinks out;
  out.drawn = probedPartialLinks(1, {kind}, count);
  for (const ProbedLink& drawn : out.drawn) out.links.push_back(drawn.link());
  return out;
}

void exactPerLink(benchmark::State& state, OccluderKind kind, int degree, double tolerance,
                  ExactOuterMethod outer, int count = kLinksPerKind) {
  const KindLinks links = partialLinks(kind, count);
  ExactGoldOptions options;
  options.tolerance = tolerance;
  options.outer = outer;
  if (kind == OccluderKind::soup) options.maxEvaluations = 20000;
  double points = 0.0, worst = 0.0, lines = 0.0, jumps = 0.0, apart = 0.0;
  for (auto _ : state) {
    points = 0.0;
    worst = 0.0;
    lines = 0.0;
    jumps = 0.0;
    apart = 0.0;
    for (const Link& link : links.links) {
      const ExactGold gold = exactGold(link, degree, options);
      points += double(gold.receiverPoints);
      lines += gold.outer == ExactOuterMethod::criticalLines ? 1.0 : 0.0;
      jumps += gold.outer == ExactOuterMethod::jumpLines ? 1.0 : 0.0;
      apart += gold.unoccludedApart ? 1.0 : 0.0;
      worst = std::max(worst, gold.couplingError.maxCoeff() / gold.coupling.cwiseAbs().maxCoeff());
      benchmark::DoNotOptimize(gold.coupling.data());
    }
  }
  state.counters["receiver_points"] = points / double(links.links.size());
  state.counters["by_critical_lines"] = lines / double(links.links.size());
  state.counters["by_jump_lines"] = jumps / double(links.links.size());
  state.counters["unoccluded_apart"] = apart / double(links.links.size());
  state.counters["max_relative_error"] = worst;
  state.counters["links"] = double(links.links.size());
}

void densePerLink(benchmark::State& state, OccluderKind kind, int degree,
                  int count = kLinksPerKind) {
  const KindLinks links = partialLinks(kind, count);
  GoldOptions options;
  options.method = GoldMethod::stratified;
  options.denseStrata = 16;
  options.denseReplicates = 8;
  double worst = 0.0;
  for (auto _ : state) {
    worst = 0.0;
    for (const Link& link : links.links) {
      const GoldReference gold = goldReference(link, degree, 5, options);
      worst = std::max(worst, gold.couplingError.maxCoeff() / gold.coupling.cwiseAbs().maxCoeff());
      benchmark::DoNotOptimize(gold.coupling.data());
    }
  }
  state.counters["max_relative_error"] = worst;
  state.counters["links"] = double(links.links.size());
}

constexpr ExactOuterMethod kLines = ExactOuterMethod::criticalLines;
constexpr ExactOuterMethod kGenzMalik = ExactOuterMethod::genzMalik;

// The study configs' tolerance (exact_tolerance 3e-4), the earlier ones (1e-6 at degree 0,
// 1e-5 at degree 2) and the default 1e-7.
#define GOLD_BENCHMARKS(kind, name)                                                           \
  BENCHMARK_CAPTURE(densePerLink, name##_d0, kind, 0)->Unit(benchmark::kMillisecond);         \
  BENCHMARK_CAPTURE(exactPerLink, name##_d0_3e4, kind, 0, 3e-4, kLines)                       \
      ->Unit(benchmark::kMillisecond);                                                        \
  BENCHMARK_CAPTURE(exactPerLink, name##_d0_1e6, kind, 0, 1e-6, kLines)                       \
      ->Unit(benchmark::kMillisecond);                                                        \
  BENCHMARK_CAPTURE(exactPerLink, name##_d0_1e6_genz_malik, kind, 0, 1e-6, kGenzMalik)        \
      ->Unit(benchmark::kMillisecond);                                                        \
  BENCHMARK_CAPTURE(exactPerLink, name##_d0_1e7, kind, 0, 1e-7, kLines)                       \
      ->Unit(benchmark::kMillisecond);                                                        \
  BENCHMARK_CAPTURE(exactPerLink, name##_d0_1e7_genz_malik, kind, 0, 1e-7, kGenzMalik)        \
      ->Unit(benchmark::kMillisecond);                                                        \
  BENCHMARK_CAPTURE(densePerLink, name##_d2, kind, 2)->Unit(benchmark::kMillisecond);         \
  BENCHMARK_CAPTURE(exactPerLink, name##_d2_3e4, kind, 2, 3e-4, kLines)                       \
      ->Unit(benchmark::kMillisecond);                                                        \
  BENCHMARK_CAPTURE(exactPerLink, name##_d2_1e5, kind, 2, 1e-5, kLines)                       \
      ->Unit(benchmark::kMillisecond);                                                        \
  BENCHMARK_CAPTURE(exactPerLink, name##_d2_1e5_genz_malik, kind, 2, 1e-5, kGenzMalik)        \
      ->Unit(benchmark::kMillisecond);                                                        \
  BENCHMARK_CAPTURE(exactPerLink, name##_d2_1e7, kind, 2, 1e-7, kLines)                       \
      ->Unit(benchmark::kMillisecond);                                                        \
  BENCHMARK_CAPTURE(exactPerLink, name##_d2_1e7_genz_malik, kind, 2, 1e-7, kGenzMalik)        \
      ->Unit(benchmark::kMillisecond)

GOLD_BENCHMARKS(OccluderKind::oneBlocker, one_blocker);
GOLD_BENCHMARKS(OccluderKind::severalBlockers, several_blockers);
GOLD_BENCHMARKS(OccluderKind::slats, slats);
// The same at the study's tolerance on 24 links of each kind (the first 6 are those above),
// a wider sample of what the study meets: the `wide_` rows.
constexpr int kWideLinks = 24;
#define WIDE_GOLD_BENCHMARKS(kind, name)                                                      \
  BENCHMARK_CAPTURE(densePerLink, wide_##name##_d0, kind, 0, kWideLinks)                      \
      ->Unit(benchmark::kMillisecond);                                                        \
  BENCHMARK_CAPTURE(exactPerLink, wide_##name##_d0_3e4, kind, 0, 3e-4, kLines, kWideLinks)    \
      ->Unit(benchmark::kMillisecond);                                                        \
  BENCHMARK_CAPTURE(densePerLink, wide_##name##_d2, kind, 2, kWideLinks)                      \
      ->Unit(benchmark::kMillisecond);                                                        \
  BENCHMARK_CAPTURE(exactPerLink, wide_##name##_d2_3e4, kind, 2, 3e-4, kLines, kWideLinks)    \
      ->Unit(benchmark::kMillisecond)

WIDE_GOLD_BENCHMARKS(OccluderKind::oneBlocker, one_blocker);
WIDE_GOLD_BENCHMARKS(OccluderKind::severalBlockers, several_blockers);
WIDE_GOLD_BENCHMARKS(OccluderKind::slats, slats);
BENCHMARK_CAPTURE(densePerLink, soup_d0, OccluderKind::soup, 0)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(exactPerLink, soup_d0_1e7_capped, OccluderKind::soup, 0, 1e-7, kLines)
    ->Unit(benchmark::kMillisecond);

// The polygon union the exact gold forms where shadows overlap, by the two libraries it could
// use: `count` overlapping convex quadrilaterals (random, fixed seed) in the unit square.
std::vector<std::vector<std::array<double, 2>>> overlappingQuads(int count) {
  std::mt19937_64 random(4);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  std::vector<std::vector<std::array<double, 2>>> quads;
  for (int q = 0; q < count; ++q) {
    const double cx = 0.3 + 0.4 * uniform(random), cy = 0.3 + 0.4 * uniform(random);
    const double angle = 6.283185307179586 * uniform(random);
    const double a = 0.1 + 0.2 * uniform(random), b = 0.1 + 0.2 * uniform(random);
    const double c = std::cos(angle), s = std::sin(angle);
    quads.push_back({{cx + c * a - s * b, cy + s * a + c * b},
                     {cx - c * a - s * b, cy - s * a + c * b},
                     {cx - c * a + s * b, cy - s * a - c * b},
                     {cx + c * a + s * b, cy + s * a - c * b}});
  }
  return quads;
}

void unionClipper(benchmark::State& state) {
  const auto quads = overlappingQuads(int(state.range(0)));
  constexpr double kScale = 17592186044416.0;  // 2^44, as in reference/shadow_union.cpp
  double area = 0.0;
  for (auto _ : state) {
    ClipperLib::Paths paths(quads.size());
    for (std::size_t q = 0; q < quads.size(); ++q) {
      for (const auto& p : quads[q]) {
        paths[q].push_back({ClipperLib::cInt(std::llround(p[0] * kScale)),
                            ClipperLib::cInt(std::llround(p[1] * kScale))});
      }
    }
    ClipperLib::Clipper clipper;
    clipper.AddPaths(paths, ClipperLib::ptSubject, true);
    ClipperLib::Paths united;
    clipper.Execute(ClipperLib::ctUnion, united, ClipperLib::pftNonZero, ClipperLib::pftNonZero);
    area = 0.0;
    for (const auto& path : united) area += ClipperLib::Area(path);
    benchmark::DoNotOptimize(area);
  }
  state.counters["area"] = std::fabs(area) / (kScale * kScale);
}

void unionBoostGeometry(benchmark::State& state) {
  namespace bg = boost::geometry;
  using Point = bg::model::d2::point_xy<double>;
  using Polygon = bg::model::polygon<Point, false>;  // counter-clockwise
  using MultiPolygon = bg::model::multi_polygon<Polygon>;
  const auto quads = overlappingQuads(int(state.range(0)));
  double area = 0.0;
  for (auto _ : state) {
    MultiPolygon united;
    for (const auto& quad : quads) {
      Polygon polygon;
      for (const auto& p : quad) bg::append(polygon.outer(), Point(p[0], p[1]));
      bg::correct(polygon);
      MultiPolygon next;
      bg::union_(united, polygon, next);
      united = std::move(next);
    }
    area = bg::area(united);
    benchmark::DoNotOptimize(area);
  }
  state.counters["area"] = area;
}

// The outline of the union (what the exact gold takes; reference/union_outline.h), on the
// same quadrilaterals: its pieces, and their area by the shoelace sum over them.
void unionOutline(benchmark::State& state) {
  const auto quads = overlappingQuads(int(state.range(0)));
  std::vector<SourceRing> rings;
  std::vector<Eigen::Vector4d> bounds;
  std::vector<std::vector<std::uint32_t>> onBorder;
  std::vector<std::size_t> members;
  for (const auto& quad : quads) {
    SourceRing ring;
    Eigen::Vector4d box(1e300, 1e300, -1e300, -1e300);
    for (const auto& p : quad) {
      ring.push_back({p[0], p[1]});
      box = {std::min(box[0], p[0]), std::min(box[1], p[1]), std::max(box[2], p[0]),
             std::max(box[3], p[1])};
    }
    if (ringArea(ring) < 0.0) std::reverse(ring.begin(), ring.end());
    members.push_back(rings.size());
    rings.push_back(ring);
    bounds.push_back(box);
    onBorder.push_back(std::vector<std::uint32_t>(ring.size(), 0));
  }
  const SourceRing border = {{-1, -1}, {2, -1}, {2, 2}, {-1, 2}};
  UnionOutline outline;
  VisibleRings pieces;
  double area = 0.0;
  for (auto _ : state) {
    pieces.clear();
    const bool closed = outline.add(rings, members, bounds, onBorder, border, 1.0, pieces);
    benchmark::DoNotOptimize(closed);
    area = 0.0;
    for (std::size_t s = 0; s < pieces.segmentCount(); ++s) {
      const Eigen::Vector2d& a = pieces.segmentStart(s);
      const Eigen::Vector2d& b = pieces.segmentEnd(s);
      area += 0.5 * (a.x() * b.y() - a.y() * b.x());
    }
    benchmark::DoNotOptimize(area);
  }
  state.counters["area"] = area;
  state.counters["pieces"] = double(pieces.segmentCount());
}

BENCHMARK(unionClipper)->Arg(2)->Arg(6)->Arg(20)->Unit(benchmark::kMicrosecond);
BENCHMARK(unionOutline)->Arg(2)->Arg(6)->Arg(20)->Unit(benchmark::kMicrosecond);
BENCHMARK(unionBoostGeometry)->Arg(2)->Arg(6)->Arg(20)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace radquad

// One thread: the exact gold spreads its receiver points over threads, the dense gold does
// not; per-link CPU time is what compares.
int main(int argc, char** argv) {
  tbb::global_control oneThread(tbb::global_control::max_allowed_parallelism, 1);
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
