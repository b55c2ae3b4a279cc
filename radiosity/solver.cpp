#include "radiosity/solver.h"

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <numbers>
#include <utility>

#include "kernel/coupling.h"
#include "kernel/occluder_scene.h"
#include "quadrature/adaptive_gauss.h"
#include "quadrature/random/philox.h"
#include "radiosity/coupling_store.h"
#include "radiosity/gauss_tables.h"
#include "radiosity/kernel_curvature.h"
#include "radiosity/link_integration.h"
#include "radiosity/near_field.h"
#include "radiosity/solver_impl.h"

namespace radquad {

Solver::Solver(const Scene& scene, SolverOptions options)
    : scene_(scene), options_(std::move(options)) {
  impl_ = std::make_unique<Impl>(scene, options_.degree, options_.droppedOrders);
  hierarchy_ = std::make_unique<Hierarchy>(scene, options_.degree);
  double largestArea = 0.0, totalArea = 0.0, emittedPower = 0.0;
  for (const ScenePatch& patch : scene.patches) {
    largestArea = std::max(largestArea, patch.patch.area);
    totalArea += patch.patch.area;
    emittedPower += patch.emission.maxCoeff() * patch.patch.area;
  }
  radiosityScale_ = emittedPower / totalArea;
  for (const ScenePatch& patch : scene.patches) {
    for (int c = 0; c < 3; ++c) {
      largestReflectance_[std::size_t(c)] =
          std::max(largestReflectance_[std::size_t(c)], patch.reflectance[c]);
    }
  }
  minArea_ = options_.minArea > 0.0 ? options_.minArea : 1e-4 * largestArea;
}

Solver::~Solver() = default;

std::size_t Solver::computeCouplings() {
  const auto start = std::chrono::steady_clock::now();
  updateSourcePoints();
  const std::uint64_t checksBefore = statistics_.ruleCheckEvaluations;
  HugePageVector<int> todo;
  HugePageVector<GaussPointCounts> rules;
  std::vector<bool> again;
  // The links that may need a (new) coupling: found in parallel, block by block, and taken in
  // link order. After the first passes, with fixed rules, only new links are; a near-field
  // link's coupling does not depend on a rule, so it is integrated once.
  const auto mayNeedCoupling = [&](const SolverLink& link) {
    if (!link.active) return false;
    if (link.coupling.computed) {
      return !link.nearField &&
             sourcePoints_[std::size_t(link.source)] != link.coupling.sourcePoints;
    }
    // A link whose source has no radiosity yet carries nothing: it is integrated once its
    // source has some (with every rule choice), so that the adaptive choice sees the
    // source's coefficients rather than zeros. A receiver that reflects nothing (an emitter,
    // a black surface) multiplies what it gathers by 0: its links are never integrated.
    const int patch = (*hierarchy_)[link.receiver].patch;
    if (!(scene_.patches[std::size_t(patch)].reflectance.maxCoeff() > 0.0)) return false;
    return !(*hierarchy_)[link.source].radiosity.isZero(0.0);
  };
  for (const int k : linksWhere(links_, mayNeedCoupling)) {
    SolverLink& link = links_[std::size_t(k)];
    link.coupling.sourcePoints = sourcePoints_[std::size_t(link.source)];
    const GaussPointCounts rule = link.nearField
                                      ? GaussPointCounts{}
                                      : chooseRule(link, &statistics_.ruleCheckEvaluations);
    if (link.coupling.computed && rule == link.coupling.rule) continue;
    if (link.coupling.computed) ++statistics_.recomputations;
    todo.push_back(k);
    rules.push_back(rule);
    again.push_back(link.coupling.computed);
  }
  // Slots and kept columns change below: the gather table is built again.
  if (!todo.empty()) impl_->gatherCurrent = false;
  const auto chosen = std::chrono::steady_clock::now();
  // Storage for the links' kept columns (untimed: allocation, not integration): a product
  // rule keeps min(Su, n) x min(Sv, n) columns, a near-field link all n^2
  // (source_projection.h). A link whose width changes moves to a slot of the new width.
  const int n = options_.degree + 1;
  for (std::size_t k = 0; k < todo.size(); ++k) {
    SolverLink& link = links_[std::size_t(todo[k])];
    const std::array<int, 2> kept =
        link.nearField ? std::array<int, 2>{n, n}
                       : std::array<int, 2>{std::min(rules[k][2], n), std::min(rules[k][3], n)};
    if (link.coupling.slot >= 0 && kept != link.coupling.gatherPoints) {
      impl_->couplings.release(keptColumns(link), std::exchange(link.coupling.slot, -1));
    }
    link.coupling.gatherPoints = kept;
    if (link.coupling.slot < 0) link.coupling.slot = impl_->couplings.allocate(keptColumns(link));
  }
  const auto stored = std::chrono::steady_clock::now();
  HugePageVector<std::uint64_t> rays(todo.size(), 0), points(todo.size(), 0);
  const std::vector<int> noCandidates;
  tbb::parallel_for(std::size_t(0), todo.size(), [&](std::size_t k) {
    SolverLink& link = links_[std::size_t(todo[k])];
    const GaussPointCounts& rule = rules[k];
    const bool partial = link.visibility == LinkClass::kPartial;
    const Link kernelLink{(*hierarchy_)[link.receiver].geometry,
                          (*hierarchy_)[link.source].geometry,
                          partial ? &impl_->occluders : nullptr};
    const int functions = n * n;
    Eigen::MatrixXd& whole = impl_->scratch.local();
    whole.resize(functions, functions);
    const Eigen::Map<Eigen::MatrixXd> coupling(whole.data(), functions, functions);
    LinkIntegrationCounts counts;
    if (link.nearField) {
      points[k] = impl_->nearField.local()
                      .integrate(kernelLink, impl_->occluders.polygons(),
                                 partial ? link.candidates : noCandidates, options_.degree,
                                 coupling)
                      .points;
    } else {
      counts = impl_->integrators.local().integrate(kernelLink, rule, impl_->tables, coupling);
      // A product rule's coupling keeps the columns of its source points' orders only
      // (source_projection.h).
      if (link.coupling.gatherPoints != std::array<int, 2>{n, n}) {
        impl_->projection.compact(link.coupling.gatherPoints[0], link.coupling.gatherPoints[1],
                                  whole.data());
      }
    }
    const Eigen::Index count = Eigen::Index(functions) * keptColumns(link);
    Eigen::Map<Eigen::VectorXf>(impl_->couplings.data(keptColumns(link), link.coupling.slot), count) =
        Eigen::Map<const Eigen::VectorXd>(whole.data(), count).cast<float>();
    link.coupling.kernelEvaluations = counts.kernelEvaluations;
    link.coupling.rule = rule;
    link.coupling.computed = true;
    rays[k] = counts.raysCast;
  });
  for (std::size_t k = 0; k < todo.size(); ++k) {
    statistics_.kernelEvaluations += links_[std::size_t(todo[k])].coupling.kernelEvaluations;
    if (again[k]) {
      statistics_.recomputationEvaluations += links_[std::size_t(todo[k])].coupling.kernelEvaluations;
    }
    statistics_.integrationRays += rays[k];
    statistics_.nearFieldPoints += points[k];
    statistics_.nearFieldLinks += points[k] > 0 ? 1 : 0;
  }
  statistics_.kernelEvaluations += statistics_.ruleCheckEvaluations - checksBefore;
  statistics_.couplingComputations += todo.size();
  statistics_.couplingSeconds +=
      std::chrono::duration<double>(chosen - start).count() +
      std::chrono::duration<double>(std::chrono::steady_clock::now() - stored).count();
  return todo.size();
}

// The elements' lists as a pass over every link would make them (each element's active
// links, in link order), from the changes since they were last made: a link only ever goes
// from active to inactive (split, or classified occluded when it is created), and links are
// only appended, so each list keeps its links that are still active, in order, followed by the
// active links created since, in order. The first call (no link listed yet, every list empty)
// lists every active link.
void Solver::updateElementLinks() {
  impl_->gatherCurrent = false;
  std::vector<int> receivers;
  receivers.reserve(splitSinceListed_.size());
  for (const int k : splitSinceListed_) {
    if (std::size_t(k) < listedLinks_) receivers.push_back(links_[std::size_t(k)].receiver);
  }
  std::sort(receivers.begin(), receivers.end());
  receivers.erase(std::unique(receivers.begin(), receivers.end()), receivers.end());
  tbb::parallel_for(std::size_t(0), receivers.size(), [&](std::size_t r) {
    std::erase_if((*hierarchy_)[receivers[r]].links,
                  [&](int k) { return !links_[std::size_t(k)].active; });
  });
  for (std::size_t k = listedLinks_; k < links_.size(); ++k) {
    if (links_[k].active) (*hierarchy_)[links_[k].receiver].links.push_back(int(k));
  }
  listedLinks_ = links_.size();
  splitSinceListed_.clear();
}

void Solver::countLinks() {
  statistics_.unoccludedLinks = statistics_.partialLinks = statistics_.occludedLinks = 0;
  for (const SolverLink& link : links_) {
    if (link.visibility == LinkClass::kOccluded && !link.split) {
      ++statistics_.occludedLinks;
    } else if (link.active) {
      ++(link.visibility == LinkClass::kUnoccluded ? statistics_.unoccludedLinks
                                                   : statistics_.partialLinks);
    }
  }
}

std::string Solver::divergence() const {
  double emission = 0.0, reflectance = 0.0;
  for (const ScenePatch& patch : scene_.patches) {
    emission = std::max(emission, patch.emission.maxCoeff());
    reflectance = std::max(reflectance, patch.reflectance.maxCoeff());
  }
  const double bound = 10.0 * emission / (1.0 - reflectance);
  for (std::size_t p = 0; p < scene_.patches.size(); ++p) {
    const Eigen::Vector3d mean = (*hierarchy_)[hierarchy_->root(int(p))].meanRadiosity();
    if (!mean.allFinite() || mean.cwiseAbs().maxCoeff() > bound) {
      return describePatch(scene_, p) + " has mean radiosity " + std::to_string(mean.maxCoeff()) +
             ", beyond ten times the physical bound " + std::to_string(bound / 10.0) +
             " (largest emission over 1 - largest reflectance)";
    }
  }
  return {};
}

// A converged solution that creates energy or has negative radiosity is a failure.
void Solver::checkSolution() {
  const FormFactorSums& sums = statistics_.formFactorSums;
  char text[200];
  if (sums.violations > 0) {
    std::snprintf(text, sizeof text,
                  "%zu leaf elements receive more than 1 + %g of a uniform radiosity, which "
                  "refinement cannot lower; the largest, %.4f, on ",
                  sums.violations, kFormFactorSumTolerance, sums.maximum);
    statistics_.failure = text + describeElement(sums.element);
  }
  for (std::size_t p = 0; p < scene_.patches.size() && statistics_.failure.empty(); ++p) {
    const Eigen::Vector3d mean = (*hierarchy_)[hierarchy_->root(int(p))].meanRadiosity();
    // Rounding can leave an unlit patch a hair below 0.
    if (mean.minCoeff() < -1e-9 * radiosityScale_) {
      std::snprintf(text, sizeof text, " has a negative mean radiosity, %.6g", mean.minCoeff());
      statistics_.failure = describePatch(scene_, p) + text;
    }
  }
  statistics_.converged = statistics_.failure.empty();
}

bool Solver::memoryExceeded(const char* phase) {
  if (!budgetExceeded_.empty()) return true;
  const std::size_t resident = residentBytes();
  if (resident <= options_.maxMemoryBytes) return false;
  constexpr double kMiB = 1024.0 * 1024.0;
  char text[320];
  std::snprintf(text, sizeof text,
                "the memory budget (%.0f MiB) was reached during %s: %.0f MiB resident with "
                "%zu elements and %zu links; raise --max-memory, or refine less (a larger "
                "--bf-eps or --min-area)",
                double(options_.maxMemoryBytes) / kMiB, phase, double(resident) / kMiB,
                hierarchy_->size(), links_.size());
  budgetExceeded_ = text;
  return true;
}

void Solver::solve() {
  const auto start = std::chrono::steady_clock::now();
  auto elapsed = [&] {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  };
  createInitialLinks();
  // Hanrahan, Salzman and Aupperle's scheme: refine, iterate until the radiosity settles,
  // refine again with the settled radiosity; done when a refinement pass splits nothing.
  double error = std::numeric_limits<double>::infinity();
  std::size_t active = 0;  // active links, for the progress reports
  for (int iteration = 1; iteration <= options_.maxIterations; ++iteration) {
    // Refinement is checked once the radiosity has settled, and at once when the iterations
    // show couplings that create energy (settleEstimate): refining them is the remedy.
    const bool recheck = iteration == 1 || error < options_.tolerance || energyCreated_;
    bool refined = budgetExceeded_.empty() && recheck && refinementPass();
    // Once the oracle splits nothing more, the leaves whose receiver sums exceed 1 have the
    // links received by their ancestors split (form_factor_check.cpp).
    if (recheck && !refined && iteration > 1 && budgetExceeded_.empty() &&
        markSumViolations() > 0) {
      refined = refinementPass();
    }
    if (!budgetExceeded_.empty()) {
      statistics_.failure = budgetExceeded_;
      break;
    }
    if (recheck && !refined && iteration > 1) {
      statistics_.converged = true;
      break;
    }
    // The elements' lists of active links change only when links are created or split.
    if (iteration == 1 || refined) updateElementLinks();
    if (computeCouplings() > 0 || refined) restartIterationHistory();
    if (memoryExceeded("the coupling integration")) {
      statistics_.failure = budgetExceeded_;
      break;
    }
    snapshotRadiosity();
    gather();
    const std::array<double, 3> changes = pushPull();
    const double change = *std::max_element(changes.begin(), changes.end());
    error = settleEstimate(changes);
    statistics_.iterations = iteration;
    statistics_.finalChange = change;
    statistics_.finalError = error;
    // With physical couplings (form factor sums <= 1) no radiosity exceeds the largest
    // emission over (1 - the largest reflectance); ten times that bound, or a value that is
    // not finite, is divergence.
    const std::string diverged = divergence();
    if (!diverged.empty()) {
      statistics_.failure = "diverged at iteration " + std::to_string(iteration) + ": " + diverged;
      break;
    }
    if (options_.progress) {
      // Links change activity only when they are created or split (classification included).
      if (iteration == 1 || refined) {
        active = 0;
        for (const SolverLink& link : links_) active += link.active ? 1 : 0;
      }
      options_.progress(SolveProgress{iteration, active, hierarchy_->size(),
                                      statistics_.kernelEvaluations, change, elapsed()});
    }
  }
  if (!statistics_.converged && statistics_.failure.empty()) {
    statistics_.failure = "no convergence within " + std::to_string(options_.maxIterations) +
                          " iterations (last relative change " +
                          std::to_string(statistics_.finalChange) + ", estimated error " +
                          std::to_string(statistics_.finalError) + ")";
  }
  updateElementLinks();
  checkFormFactorSums();
  if (statistics_.converged) checkSolution();
  countLinks();
  statistics_.elapsedSeconds = elapsed();
  // The solution is in the hierarchy; the couplings (about 1 GiB for a cubic cornell solve)
  // are released so that a solver kept for its solution does not hold them.
  statistics_.couplingStoreBytes = impl_->couplings.bytes();
  impl_->couplings = CouplingStore(hierarchy_->functions());
  impl_->gatherEntries = {};
  impl_->gatherBegin = {};
  impl_->gatherCurrent = false;
  for (SolverLink& link : links_) link.coupling.slot = -1;
}

}  // namespace radquad
