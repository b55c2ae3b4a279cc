// The Jacobi iterations' push/pull step, their error estimate and their acceleration.
//
// With the couplings fixed, a Jacobi step is B <- B^e + rho K B, whose error shrinks by the
// spectral radius r of rho K per step: about the largest reflectance in a closed scene, the
// mode that decays slowest being the scene's overall brightness. The change of a step then
// understates the error left by r / (1 - r) (99 times at a reflectance of 0.99), and the steps
// needed grow like 1 / (1 - r). So, per colour channel (the channels are independent systems):
//   - the error is estimated as change r / (1 - r), with r the ratio of the last two changes,
//     and the iterations settle when that estimate, not the change, is below the tolerance;
//   - once the ratio has held steady over three steps (the slowest mode dominates the change),
//     the radiosity is extrapolated along that mode, B <- B + (B - B_previous) r / (1 - r)
//     (Aitken's delta-squared process applied to the whole vector), which removes most of the
//     remaining error at once. Every element is extrapolated alike: parents are pulls of their
//     children, a linear map, so the hierarchy stays consistent.
// The history restarts whenever refinement or new couplings change the system.
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "radiosity/solver_impl.h"

namespace radquad {
namespace {

// Ratios r of successive changes within kSteadyRatio (1 - r) of each other count as settled:
// the extrapolation factor r / (1 - r) is then known to a few per cent.
constexpr double kSteadyRatio = 0.02;
// A ratio beyond rho + kEnergyMargin (1 - rho), rho the largest reflectance, amplifies
// radiosity by more than 1 / (1 - rho) can: couplings that create energy.
constexpr double kEnergyMargin = 0.1;
// Extrapolation only where the slowest mode decays this slowly (faster ones need no help).
constexpr double kSlowestWorthExtrapolating = 0.5;

}  // namespace

void Solver::restartIterationHistory() {
  iterationChanges_.clear();
  energyCreated_ = false;
}

void Solver::snapshotRadiosity() {
  const std::size_t functions = std::size_t(hierarchy_->functions());
  previousRadiosity_.resize(hierarchy_->size() * functions * 3);
  tbb::parallel_for(std::size_t(0), hierarchy_->size(), [&](std::size_t e) {
    const Coefficients& b = (*hierarchy_)[int(e)].radiosity;
    std::copy(b.data(), b.data() + b.size(), previousRadiosity_.data() + e * functions * 3);
  });
}

// Pushes and pulls every patch; returns the relative L2 change of the patch-level radiosity
// per channel since snapshotRadiosity (the roots' coefficients are the projections of B on
// each patch's own basis: their Euclidean norm is the L2 norm of that projection).
std::array<double, 3> Solver::pushPull() {
  const std::size_t patches = scene_.patches.size();
  const std::size_t functions = std::size_t(hierarchy_->functions());
  std::vector<Eigen::Array3d> change(patches), norm(patches);
  tbb::parallel_for(std::size_t(0), patches, [&](std::size_t p) {
    const int root = hierarchy_->root(int(p));
    hierarchy_->pushPull(int(p));
    const Coefficients& after = (*hierarchy_)[root].radiosity;
    const Eigen::Map<const Coefficients> before(
        previousRadiosity_.data() + std::size_t(root) * functions * 3, after.rows(), 3);
    change[p] = (after - before).colwise().squaredNorm().transpose().array();
    norm[p] = after.colwise().squaredNorm().transpose().array();
  });
  Eigen::Array3d totalChange = Eigen::Array3d::Zero(), totalNorm = Eigen::Array3d::Zero();
  for (std::size_t p = 0; p < patches; ++p) {
    totalChange += change[p];
    totalNorm += norm[p];
  }
  std::array<double, 3> relative{};
  for (int c = 0; c < 3; ++c) {
    relative[std::size_t(c)] =
        totalNorm[c] > 0.0 ? std::sqrt(totalChange[c] / totalNorm[c]) : 0.0;
    lastAbsoluteChange_[std::size_t(c)] = std::sqrt(totalChange[c]);
  }
  return relative;
}

double Solver::settleEstimate(const std::array<double, 3>& change) {
  // The ratios use the changes' absolute sizes (the radiosity itself grows while light
  // builds up); the error is relative, as the tolerance.
  iterationChanges_.push_back(lastAbsoluteChange_);
  const std::size_t count = iterationChanges_.size();
  double error = 0.0;
  std::array<double, 3> factor{};  // extrapolation factor per channel (0: none)
  bool extrapolate = false;
  const auto ratioAt = [&](std::size_t k, std::size_t c) {
    return iterationChanges_[k][c] / iterationChanges_[k - 1][c];
  };
  for (std::size_t c = 0; c < 3; ++c) {
    if (change[c] == 0.0) continue;
    if (count < 2 || !(iterationChanges_[count - 2][c] > 0.0)) {
      error = std::numeric_limits<double>::infinity();
      continue;
    }
    const double ratio = ratioAt(count - 1, c);
    if (!(ratio < 1.0)) {
      error = std::numeric_limits<double>::infinity();
      continue;
    }
    error = std::max(error, change[c] * ratio / (1.0 - ratio));
    if (count < 4 || ratio < kSlowestWorthExtrapolating) continue;
    // Physical couplings (receiver sums at most 1) cannot make the slowest mode decay more
    // slowly than the largest reflectance: a steady ratio above it means couplings that
    // create energy, whose fixed point lies beyond the physical bound. No extrapolation
    // then; the solve refines (Solver::solve).
    const double reflectance = largestReflectance_[c];
    if (ratio > reflectance + kEnergyMargin * (1.0 - reflectance)) {
      energyCreated_ = true;
      continue;
    }
    bool steady = true;
    for (std::size_t back = 2; back <= 3 && steady; ++back) {
      steady = std::abs(ratioAt(count - back, c) - ratio) <= kSteadyRatio * (1.0 - ratio);
    }
    if (steady) {
      factor[c] = ratio / (1.0 - ratio);
      extrapolate = true;
    }
  }
  if (!extrapolate) return error;
  const std::size_t functions = std::size_t(hierarchy_->functions());
  tbb::parallel_for(std::size_t(0), hierarchy_->size(), [&](std::size_t e) {
    Coefficients& b = (*hierarchy_)[int(e)].radiosity;
    const Eigen::Map<const Coefficients> before(previousRadiosity_.data() + e * functions * 3,
                                                b.rows(), 3);
    for (int c = 0; c < 3; ++c) {
      if (factor[std::size_t(c)] > 0.0) b.col(c) += factor[std::size_t(c)] * (b.col(c) - before.col(c));
    }
  });
  ++statistics_.extrapolations;
  // The extrapolated radiosity starts a new history; its error is not known yet.
  restartIterationHistory();
  return std::numeric_limits<double>::infinity();
}

}  // namespace radquad
