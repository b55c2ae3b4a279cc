// An unbiased Monte Carlo reference for whole radiosity scenes: every patch's mean radiosity
// B_i = (1/A_i) int_{A_i} B dA per colour channel, with its standard error. It is the
// yardstick of the hierarchical Galerkin solver and shares no integration code with it (no
// couplings, links, quadrature rules or solver visibility): only the scene description, the
// Philox generator and the Embree device.
//
// Equation (the solver's): B(x) = E_i + rho_i I(x), I(x) = int G(x,y) B(y) dA_y,
// G = cos_x cos_y V / (pi r^2), cosines clamped at 0; a patch emits and receives on its
// normal's side only and stops rays from both sides.
//
// Estimator, per patch i and sample k:
// - x uniform on patch i, stratified: with m = floor(sqrt(N)), samples k < m^2 are jittered
//   in cell (k / m, k % m) of an m x m grid over (u,v), the other N - m^2 are uniform (every
//   sample set is then uniform on average, so the mean is unbiased). The sample's estimate is
//   E_i + rho_i I^(x).
// - I^ at a vertex x on patch p: next-event estimation to every emitter e (a patch with an
//   emission channel > 0) other than p's plane mates (trace_scene.h: p, and the patches in its
//   plane it touches, such as the other face of a two-sided panel) with one uniform point y on
//   e, weighted E_e G V / (1/A_e + G); plus one cosine-weighted direction, whose first hit y
//   on patch h (p's plane mates ignored; on a two-sided surface, the face turned to the ray)
//   adds E_h G / (G + 1/A_h) when it is h's front side and h emits; the path then continues
//   from y with throughput *= rho_h. These are the balance-heuristic weights of the two strategies
//   in area measure (pdfs 1/A_e and G), so both terms are bounded by E_e, even for points
//   touching an emitter. A back-side hit or an escaping ray ends the path with nothing.
// - Russian roulette from the fourth bounce on: survival probability
//   q = min(1, largest channel of the throughput), throughput /= q on survival.
// - A hard cap of kMaxTraceBounces bounces: since the throughput never exceeds 1, a path
//   survives each bounce past the third with probability at most rho_max (the largest
//   reflectance in the scene), so it reaches the cap with probability at most
//   rho_max^(kMaxTraceBounces - 3): below 1e-43 for any rho_max <= 0.99 (cornell's is 0.78).
//   Truncated paths are counted (`truncatedPaths`), so a bias from the cap would show.
//
// Random numbers: Philox4x32-10 keyed by the seed, block counter (sample, patch, vertex, use),
// so a sample's path is a pure function of (seed, patch, sample). Samples are traced in
// fixed chunks of kTraceChunkSamples; each chunk's count, mean and centred sum of squares are
// stored by chunk index and combined in chunk order, so the result is the same, bit for bit,
// for any thread count.
//
// Standard error: sqrt(s^2 / N), s^2 the sample variance of the N per-sample estimates, per
// channel. It treats the samples as independent; the stratified starting points make the
// true standard error smaller, so it is conservative.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <functional>
#include <vector>

#include "radiosity/scene.h"

namespace radquad {

// The largest number of samples per patch (the sample index is one 32-bit counter word).
inline constexpr std::uint64_t kMaxTraceSamples = 1'000'000'000;
inline constexpr int kMaxTraceBounces = 10000;
inline constexpr std::uint64_t kTraceChunkSamples = 1024;
inline constexpr int kRouletteAfterBounces = 3;

struct TraceProgress {
  std::uint64_t samplesDone = 0;
  std::uint64_t samplesTotal = 0;
  double elapsedSeconds = 0.0;
};

struct TraceOptions {
  std::uint64_t samples = 1;  // per patch, 1..kMaxTraceSamples
  std::uint64_t seed = 0;
  int threads = 0;            // 0: all cores
  // Called from worker threads (one at a time), at most about once a second.
  std::function<void(const TraceProgress&)> progress;
};

struct PatchTrace {
  Eigen::Vector3d meanRadiosity = Eigen::Vector3d::Zero();
  // sqrt(sample variance / N) per channel; NaN when N = 1 (no variance estimate).
  Eigen::Vector3d standardError = Eigen::Vector3d::Zero();
};

struct TraceResult {
  std::vector<PatchTrace> patches;  // scene order
  std::uint64_t paths = 0;          // samples traced, over all patches
  std::uint64_t hitRays = 0;        // first-hit rays (cosine-sampled directions)
  std::uint64_t shadowRays = 0;     // next-event visibility rays
  std::uint64_t truncatedPaths = 0; // paths stopped by kMaxTraceBounces
  double elapsedSeconds = 0.0;
};

// Throws std::invalid_argument when options.samples is outside 1..kMaxTraceSamples or the
// threads are negative, and ComputationError (kernel/input_error.h) naming the patch when an
// estimate is not finite.
TraceResult tracePatches(const Scene& scene, const TraceOptions& options);

}  // namespace radquad
