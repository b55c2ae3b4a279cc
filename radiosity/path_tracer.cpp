#include "radiosity/path_tracer.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/partitioner.h>
#include <tbb/task_arena.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <limits>
#include <mutex>
#include <numbers>
#include <stdexcept>
#include <string>

#include "kernel/input_error.h"
#include "quadrature/random/philox.h"
#include "radiosity/trace_scene.h"

namespace radquad {
namespace {

using Vec = Eigen::Vector3d;

// The fourth word of a random block's counter: what the two uniforms are for.
enum Use : std::uint32_t {
  kUseDirection = 0,  // the cosine-weighted direction leaving vertex `vertex`
  kUseRoulette = 1,   // Russian roulette on arriving at vertex `vertex`
  kUsePosition = 2,   // the starting point (vertex 0)
  kUseEmitter = 3,    // + the emitter's ordinal: the next-event point on it from `vertex`
};

struct Uniforms {
  double first;
  double second;
};

struct TracePatch {
  Patch patch;
  Vec tangent;    // edgeU normalised
  Vec bitangent;  // normal x tangent
  Vec reflectance;
  Vec emission;
  bool emits = false;
  bool reflects = false;
};

// What one chunk of samples of one patch adds up to. `mean` and `centred` (the sum of squared
// deviations from the mean) are accumulated by Welford's update, which stays accurate when
// the spread is tiny next to the mean (an emitter's radiosity).
struct ChunkSums {
  std::uint64_t count = 0;
  Vec mean = Vec::Zero();
  Vec centred = Vec::Zero();
  std::uint64_t hitRays = 0;
  std::uint64_t shadowRays = 0;
  std::uint64_t truncatedPaths = 0;

  void add(const Vec& value) {
    ++count;
    const Vec delta = value - mean;
    mean += delta / double(count);
    centred += delta.cwiseProduct(value - mean);
  }
  // Chan, Golub and LeVeque's pairwise update: this followed by `other`.
  void append(const ChunkSums& other) {
    hitRays += other.hitRays;
    shadowRays += other.shadowRays;
    truncatedPaths += other.truncatedPaths;
    if (other.count == 0) return;
    if (count == 0) {  // the update below would multiply an overflowed delta^2 by 0
      count = other.count;
      mean = other.mean;
      centred = other.centred;
      return;
    }
    const double n = double(count), m = double(other.count), total = n + m;
    const Vec delta = other.mean - mean;
    mean += delta * (m / total);
    centred += other.centred + delta.cwiseProduct(delta) * (n * m / total);
    count += other.count;
  }
};

// G(x,y) without visibility: cos_x cos_y / (pi r^2), 0 when either cosine is <= 0 or the
// points coincide. With w = y - x: cos_x = n_x.w / r, cos_y = -n_y.w / r.
double geometryTerm(const Vec& x, const Vec& nx, const Vec& y, const Vec& ny) {
  const Vec w = y - x;
  const double r2 = w.squaredNorm();
  const double cx = nx.dot(w), cy = -ny.dot(w);
  if (!(r2 > 0.0) || !(cx > 0.0) || !(cy > 0.0)) return 0.0;
  return cx * cy / (std::numbers::pi * r2 * r2);
}

class PathSampler {
 public:
  PathSampler(const Scene& scene, std::uint64_t seed, std::uint64_t samples)
      : rays_(scene), key_(philoxKey(seed)) {
    for (const ScenePatch& source : scene.patches) {
      TracePatch patch;
      patch.patch = source.patch;
      patch.tangent = source.patch.edgeU.normalized();
      patch.bitangent = source.patch.normal.cross(patch.tangent).normalized();
      patch.reflectance = source.reflectance;
      patch.emission = source.emission;
      patch.emits = source.emission.maxCoeff() > 0.0;
      patch.reflects = source.reflectance.maxCoeff() > 0.0;
      if (patch.emits) emitters_.push_back(int(patches_.size()));
      patches_.push_back(patch);
    }
    grid_ = std::uint64_t(std::sqrt(double(samples)));
    while (grid_ * grid_ > samples) --grid_;
    while ((grid_ + 1) * (grid_ + 1) <= samples) ++grid_;
  }

  // The estimate E_i + rho_i I^(x) of sample `sample` of patch `start`.
  Vec estimate(int start, std::uint32_t sample, ChunkSums& sums) const;

 private:
  Uniforms draw(std::uint32_t sample, int patch, std::uint32_t vertex, std::uint32_t use) const {
    const PhiloxCounter block = philox4x32({sample, std::uint32_t(patch), vertex, use}, key_);
    return {uniformFromWords(block[0], block[1]), uniformFromWords(block[2], block[3])};
  }
  Vec startPoint(int patch, std::uint32_t sample) const;

  TraceScene rays_;
  PhiloxKey key_;
  std::uint64_t grid_ = 1;  // floor(sqrt(samples))
  std::vector<TracePatch> patches_;
  std::vector<int> emitters_;
};

Vec PathSampler::startPoint(int patch, std::uint32_t sample) const {
  const Uniforms jitter = draw(sample, patch, 0, kUsePosition);
  double u = jitter.first, v = jitter.second;
  if (sample < grid_ * grid_) {  // a jittered cell of the grid_ x grid_ strata
    u = (double(sample / grid_) + u) / double(grid_);
    v = (double(sample % grid_) + v) / double(grid_);
  }
  return patches_[patch].patch.pointAt(u, v);
}

Vec PathSampler::estimate(int start, std::uint32_t sample, ChunkSums& sums) const {
  const TracePatch& origin = patches_[start];
  Vec value = origin.emission;
  if (!origin.reflects) return value;
  Vec x = startPoint(start, sample);
  Vec throughput = origin.reflectance;
  int p = start;
  for (std::uint32_t vertex = 0;; ++vertex) {
    const TracePatch& here = patches_[p];
    const Vec& n = here.patch.normal;
    // Next-event estimation: one point on every emitter, light-sampling weight
    // (1/A_e) / (1/A_e + G).
    for (std::size_t k = 0; k < emitters_.size(); ++k) {
      const int e = emitters_[k];
      // A patch does not light itself or its plane mates (trace_scene.h): they share its
      // plane, or are the other face of a two-sided surface, and first-hit rays ignore them too.
      if (rays_.mates(p, e)) continue;
      const TracePatch& emitter = patches_[e];
      const Uniforms point = draw(sample, start, vertex, kUseEmitter + std::uint32_t(k));
      const Vec y = emitter.patch.pointAt(point.first, point.second);
      const double g = geometryTerm(x, n, y, emitter.patch.normal);
      if (g <= 0.0) continue;
      ++sums.shadowRays;
      if (!rays_.unobstructed(x, y, p, e)) continue;
      value += throughput.cwiseProduct(emitter.emission) * (g / (1.0 / emitter.patch.area + g));
    }
    // A cosine-weighted direction (pdf cos_x / pi in solid angle, G in area measure).
    const Uniforms direction = draw(sample, start, vertex, kUseDirection);
    const double radius = std::sqrt(direction.first);
    const double phi = 2.0 * std::numbers::pi * direction.second;
    const Vec d = radius * std::cos(phi) * here.tangent + radius * std::sin(phi) * here.bitangent +
                  std::sqrt(1.0 - direction.first) * n;
    ++sums.hitRays;
    double t = 0.0;
    const int h = rays_.firstHit(x, d, p, t);
    if (h < 0) break;  // left the scene
    const TracePatch& hit = patches_[h];
    if (!(d.dot(hit.patch.normal) < 0.0)) break;  // the back side: nothing, and it stops
    // The hit point, moved onto h's plane (Embree's t is a float).
    Vec y = x + t * d;
    y -= hit.patch.normal * hit.patch.normal.dot(y - hit.patch.origin);
    if (hit.emits) {
      // Direction-sampling weight G / (G + 1/A_h); visibility is implied by the hit.
      const double g = geometryTerm(x, n, y, hit.patch.normal);
      value += throughput.cwiseProduct(hit.emission) * (g / (g + 1.0 / hit.patch.area));
    }
    if (!hit.reflects) break;
    throughput = throughput.cwiseProduct(hit.reflectance);
    if (!(throughput.maxCoeff() > 0.0)) break;
    const std::uint32_t bounces = vertex + 1;
    if (bounces > std::uint32_t(kRouletteAfterBounces)) {
      const double survival = std::min(1.0, throughput.maxCoeff());
      if (survival < 1.0) {
        if (draw(sample, start, bounces, kUseRoulette).first >= survival) break;
        throughput /= survival;
      }
    }
    if (bounces >= std::uint32_t(kMaxTraceBounces)) {
      ++sums.truncatedPaths;
      break;
    }
    x = y;
    p = h;
  }
  return value;
}

}  // namespace

TraceResult tracePatches(const Scene& scene, const TraceOptions& options) {
  using Clock = std::chrono::steady_clock;
  const Clock::time_point begin = Clock::now();
  if (options.samples < 1 || options.samples > kMaxTraceSamples) {
    throw std::invalid_argument("samples per patch must be 1.." + std::to_string(kMaxTraceSamples));
  }
  if (options.threads < 0) throw std::invalid_argument("threads must be >= 0");
  const auto seconds = [&] { return std::chrono::duration<double>(Clock::now() - begin).count(); };

  const PathSampler sampler(scene, options.seed, options.samples);
  const std::size_t patchCount = scene.patches.size();
  const std::uint64_t chunksPerPatch = (options.samples + kTraceChunkSamples - 1) / kTraceChunkSamples;
  const std::size_t chunkCount = std::size_t(chunksPerPatch * patchCount);
  std::vector<ChunkSums> chunks(chunkCount);

  std::atomic<std::uint64_t> samplesDone{0};
  std::mutex progressMutex;
  double lastReport = 0.0;
  const auto traceChunk = [&](std::size_t c) {
    const int patch = int(c / chunksPerPatch);
    const std::uint64_t first = (c % chunksPerPatch) * kTraceChunkSamples;
    const std::uint64_t last = std::min(first + kTraceChunkSamples, options.samples);
    ChunkSums& sums = chunks[c];
    for (std::uint64_t k = first; k < last; ++k) {
      sums.add(sampler.estimate(patch, std::uint32_t(k), sums));
    }
    const std::uint64_t done = samplesDone += last - first;
    if (options.progress && progressMutex.try_lock()) {
      std::lock_guard<std::mutex> lock(progressMutex, std::adopt_lock);
      const double now = seconds();
      if (now - lastReport >= 1.0) {
        lastReport = now;
        options.progress({done, options.samples * patchCount, now});
      }
    }
  };
  tbb::task_arena arena(options.threads > 0 ? options.threads : tbb::task_arena::automatic);
  arena.execute([&] {
    tbb::parallel_for(
        tbb::blocked_range<std::size_t>(0, chunkCount, 1),
        [&](const tbb::blocked_range<std::size_t>& range) {
          for (std::size_t c = range.begin(); c != range.end(); ++c) traceChunk(c);
        },
        tbb::simple_partitioner());
  });

  TraceResult result;
  result.patches.resize(patchCount);
  for (std::size_t p = 0; p < patchCount; ++p) {
    ChunkSums total;
    for (std::uint64_t c = 0; c < chunksPerPatch; ++c) total.append(chunks[p * chunksPerPatch + c]);
    PatchTrace& out = result.patches[p];
    out.meanRadiosity = total.mean;
    const double n = double(total.count);
    out.standardError = total.count > 1
                            ? Vec((total.centred / ((n - 1.0) * n)).cwiseSqrt())
                            : Vec::Constant(std::numeric_limits<double>::quiet_NaN());
    if (!total.mean.allFinite() || (total.count > 1 && !out.standardError.allFinite())) {
      // The message names the patch as describePatch (scene.cpp) does; that file is not linked.
      const std::string& name = scene.patches[p].name;
      throw ComputationError("patches[" + std::to_string(p) + "]" +
                             (name.empty() ? "" : " (" + name + ")") +
                             ": the Monte Carlo estimate of the mean radiosity is not finite");
    }
    result.paths += total.count;
    result.hitRays += total.hitRays;
    result.shadowRays += total.shadowRays;
    result.truncatedPaths += total.truncatedPaths;
  }
  result.elapsedSeconds = seconds();
  return result;
}

}  // namespace radquad
