// Adaptive Genz-Malik cubature over the unit square for a vector of integrands (the exact
// gold's outer integral, exact_gold.h), deterministic and batched:
//   - each region carries the degree-7 Genz-Malik rule (17 points in two dimensions) and its
//     embedded degree-5 rule; a component's error estimate is the two rules' difference;
//   - the run starts from a uniform grid of `initialGrid` x `initialGrid` regions, so no part
//     of the square is judged from fewer points than that grid gives it (a feature smaller
//     than a region, such as a thin shadow between its points, is invisible to the region's
//     own estimate);
//   - then it halves the regions of largest estimated error (along the axis of largest fourth
//     difference), several at a time: every region whose error the tolerance cannot absorb,
//     largest first, up to `batchRegions`; their points go to `evaluate` as one batch;
//   - it stops when every component's summed error is at most `tolerance` times the largest
//     |summed value| (plus the baseline's, when one is given), or when `maxEvaluations`
//     points are spent (converged = false).
// The regions halved and the order of every sum depend on the values alone, so the result
// is the same bits whatever `evaluate` does with threads.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

namespace radquad {

struct GenzMalikOptions {
  double tolerance = 1e-7;
  int initialGrid = 1;
  std::uint64_t maxEvaluations = 4000000;
  std::size_t batchRegions = 256;
  // A part of the whole integral known beforehand (empty: none). The tolerance is then
  // relative to the largest |baseline + summed value|: the run integrates the rest of an
  // integral whose size is the whole's. The result holds the run's own values and errors.
  std::vector<double> baseline;
};

struct GenzMalikResult {
  std::vector<double> value;
  std::vector<double> error;
  std::uint64_t points = 0;
  bool converged = false;
};

// evaluate(count, points, out): the `values` integrands at the points (s, t) = (points[2k],
// points[2k + 1]) into out[k * values + v].
using BatchIntegrand = std::function<void(std::size_t count, const double* points, double* out)>;

// The 2D rule's points per region.
constexpr int kGenzMalikPoints = 17;

GenzMalikResult genzMalik2d(std::size_t values, const BatchIntegrand& evaluate,
                            const GenzMalikOptions& options);

}  // namespace radquad
