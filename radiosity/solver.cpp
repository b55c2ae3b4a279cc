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
  minArea_ = options_.minArea > 0.0 ? options_.minArea : 1e-4 * largestArea;
}

Solver::~Solver() = default;

const char* ruleChoiceName(RuleChoice rules) {
  switch (rules) {
    case RuleChoice::kFixed:
      return "fixed";
    case RuleChoice::kAdaptive:
      return "adaptive";
    case RuleChoice::kAdaptiveNoVisibility:
      return "adaptive-novis";
  }
  return "?";
}

// Fixed: (d+1)^4. Adaptive (Gershbein 1995, Figure 4): the source's coefficient magnitudes
// are each component's RMS radiosity over the element, |B_(i,j),c| / sqrt(A_S) (the basis is
// orthonormal over the element, so int (B M)^2 dA = B^2), largest over channels c, divided by
// the scene's radiosity scale: ErrThres is then a fraction of the scene's mean emitted
// radiosity, independent of scene units and element size. A link's rule only grows: the
// report re-checks couplings after each iteration "to see if we need a better quadrature rule
// due to the energy gain"; a rule never shrinks back (that would only recompute to lose
// accuracy). The partial-visibility draw uses a generator keyed by the (receiver, source)
// element ids, so it is the same whatever the thread count.
AdaptiveGaussInput Solver::adaptiveInput(int sourceElement, double* magnitudes) const {
  const int n = options_.degree + 1;
  const Element& source = (*hierarchy_)[sourceElement];
  const double normaliser =
      radiosityScale_ > 0.0 ? 1.0 / (std::sqrt(source.geometry.area) * radiosityScale_) : 0.0;
  for (int a = 0; a < n * n; ++a) {
    magnitudes[a] = source.radiosity.row(a).cwiseAbs().maxCoeff() * normaliser;
  }
  AdaptiveGaussInput input;
  input.degree = options_.degree;
  input.magnitudes = magnitudes;
  input.errThres = options_.errThres;
  return input;
}

namespace {

// A rule's points along one side of an element, for `points` chosen per axis of a square
// (d+1 for fixed rules, Figure 4's choice for the adaptive ones): along a side r times
// longer than the other, `points` round(r) (at most GaussTables::kMaxPointsPerAxis), so that
// the points are about as far apart along both sides. The quadtree keeps an element's shape
// at every level (a 13:1 slat stays 13:1), and with d+1 points along its length its
// couplings missed the kernel's variation there (the slats scene at degree 0 converged 5% off
// on average).
int alongSide(const Patch& element, bool alongU, int points) {
  const double lengthU = element.edgeU.norm(), lengthV = element.edgeV.norm();
  const double ratio = alongU ? lengthU / lengthV : lengthV / lengthU;
  return std::min(GaussTables::kMaxPointsPerAxis, points * std::max(1, int(std::lround(ratio))));
}

}  // namespace

GaussPointCounts Solver::chooseRule(const SolverLink& link,
                                      std::uint64_t* checkEvaluations) const {
  const int n = options_.degree + 1;
  // Fixed rules: d+1 points per axis, but 2 at degree 0, where the midpoint rule overestimates
  // peaked kernels (the white furnace at degree 0 came out 9% bright with it, 3% at
  // --bf-eps 0.05; 0.8% with 2 points).
  const int fixed = std::max(n, 2);
  GaussPointCounts rule = {fixed, fixed, fixed, fixed};
  const Patch& r = (*hierarchy_)[link.receiver].geometry;
  const Patch& s = (*hierarchy_)[link.source].geometry;
  if (options_.rules != RuleChoice::kFixed) {
    double magnitudes[(kMaxAdaptiveDegree + 1) * (kMaxAdaptiveDegree + 1)];
    AdaptiveGaussInput input = adaptiveInput(link.source, magnitudes);
    input.partiallyOccluded = link.visibility == LinkClass::kPartial;
    if (options_.rules == RuleChoice::kAdaptive) {
      PhiloxStream generator(
          linkSeed(options_.seed, std::uint32_t(link.receiver), std::uint32_t(link.source)), 0);
      rule = chooseGaussRules(input, generator);
    } else {
      rule = chooseGaussRulesNoVisibility(input);
    }
  }
  // The receiver keeps the fixed rule's points (Figure 4 gives it d+1; at degree 0 the floor
  // of 2 keeps the midpoint rule's bias away, as for the fixed rules).
  rule[0] = std::max(rule[0], fixed);
  rule[1] = std::max(rule[1], fixed);
  rule = {alongSide(r, true, rule[0]), alongSide(r, false, rule[1]), alongSide(s, true, rule[2]),
          alongSide(s, false, rule[3])};
  // The kernel check (kernel_curvature.h): Figure 4 bounds the error of a reduced rule from
  // the source's radiosity alone; a source axis left with one point is the midpoint rule
  // along it, biased wherever the kernel bows, so it gets a second point there.
  if (options_.rules != RuleChoice::kFixed && options_.kernelCurvature > 0.0) {
    for (int axis = 0; axis < 2; ++axis) {
      if (rule[2 + axis] != 1) continue;
      *checkEvaluations += 3;
      if (midpointRelativeError(r, s, axis == 0) > options_.kernelCurvature) rule[2 + axis] = 2;
    }
  }
  if (link.computed) {
    for (int axis = 0; axis < 4; ++axis) rule[axis] = std::max(rule[axis], link.rule[axis]);
  }
  return rule;
}

// The source-axis points {Su, Sv} of Figure 4 without its visibility step, for every element
// (a function of the element's coefficients only). A link whose source's points are those it
// was last integrated with cannot need a larger rule: its visibility step draws from its own
// generator keyed by the link's ids, so it would choose the same rule again. Only the other
// links go through chooseRule, which keeps the per-iteration check at one comparison per link.
void Solver::updateSourcePoints() {
  const int n = options_.degree + 1;
  sourcePoints_.resize(hierarchy_->size());
  tbb::parallel_for(std::size_t(0), hierarchy_->size(), [&](std::size_t e) {
    if (options_.rules == RuleChoice::kFixed) {
      sourcePoints_[e] = {n, n};
      return;
    }
    double magnitudes[(kMaxAdaptiveDegree + 1) * (kMaxAdaptiveDegree + 1)];
    const GaussPointCounts rule = chooseGaussRulesNoVisibility(adaptiveInput(int(e), magnitudes));
    sourcePoints_[e] = {rule[2], rule[3]};
  });
}

void Solver::computeCouplings() {
  const auto start = std::chrono::steady_clock::now();
  updateSourcePoints();
  const std::uint64_t checksBefore = statistics_.ruleCheckEvaluations;
  std::vector<int> todo;
  std::vector<GaussPointCounts> rules;
  std::vector<bool> again;
  std::vector<bool> composites;
  for (std::size_t k = 0; k < links_.size(); ++k) {
    SolverLink& link = links_[k];
    if (!link.active) continue;
    const std::array<int, 2>& sourcePoints = sourcePoints_[std::size_t(link.source)];
    if (link.computed && sourcePoints == link.sourcePoints) continue;
    // A link whose source has no radiosity yet carries nothing: it is integrated once its
    // source has some (with every rule choice), so that the adaptive choice sees the
    // source's coefficients rather than zeros.
    if (!link.computed && (*hierarchy_)[link.source].radiosity.isZero(0.0)) continue;
    link.sourcePoints = sourcePoints;
    const GaussPointCounts rule = chooseRule(link, &statistics_.ruleCheckEvaluations);
    if (link.computed && rule == link.rule) continue;
    if (link.computed) ++statistics_.recomputations;
    todo.push_back(int(k));
    rules.push_back(rule);
    again.push_back(link.computed);
  }
  const auto chosen = std::chrono::steady_clock::now();
  // Storage for the links' kept columns (untimed: allocation, not integration): a product
  // rule keeps min(Su, n) x min(Sv, n) columns, a composite rule all n^2
  // (source_projection.h). A link whose width changes moves to a slot of the new width.
  const int n = options_.degree + 1;
  for (std::size_t k = 0; k < todo.size(); ++k) {
    SolverLink& link = links_[std::size_t(todo[k])];
    const bool composite =
        LinkIntegrator::composite((*hierarchy_)[link.receiver].geometry,
                                  (*hierarchy_)[link.source].geometry, options_.singularDepth);
    const std::array<int, 2> kept =
        composite ? std::array<int, 2>{n, n}
                  : std::array<int, 2>{std::min(rules[k][2], n), std::min(rules[k][3], n)};
    if (link.slot >= 0 && kept != link.gatherPoints) {
      impl_->couplings.release(keptColumns(link), std::exchange(link.slot, -1));
    }
    link.gatherPoints = kept;
    composites.push_back(composite);
    if (link.slot < 0) link.slot = impl_->couplings.allocate(keptColumns(link));
  }
  const auto stored = std::chrono::steady_clock::now();
  std::vector<std::uint64_t> rays(todo.size(), 0);
  tbb::parallel_for(std::size_t(0), todo.size(), [&](std::size_t k) {
    SolverLink& link = links_[std::size_t(todo[k])];
    const GaussPointCounts& rule = rules[k];
    const Link kernelLink{(*hierarchy_)[link.receiver].geometry,
                          (*hierarchy_)[link.source].geometry,
                          link.visibility == LinkClass::kPartial ? &impl_->occluders : nullptr};
    const int functions = n * n;
    Eigen::MatrixXd& whole = impl_->scratch.local();
    whole.resize(functions, functions);
    const LinkIntegrationCounts counts = impl_->integrators.local().integrate(
        kernelLink, rule, impl_->tables, options_.singularDepth,
        Eigen::Map<Eigen::MatrixXd>(whole.data(), functions, functions));
    // A product rule's coupling keeps the columns of its source points' orders only; a
    // composite one keeps every column, those of the orders its rule drops zeroed when they
    // are truncated (source_projection.h).
    if (link.gatherPoints != std::array<int, 2>{n, n}) {
      impl_->projection.compact(link.gatherPoints[0], link.gatherPoints[1], whole.data());
    } else if (rule[2] < n || rule[3] < n) {
      impl_->projection.dropOrders(std::min(rule[2], n), std::min(rule[3], n), whole.data());
    }
    std::memcpy(impl_->couplings.data(keptColumns(link), link.slot), whole.data(),
                sizeof(double) * std::size_t(functions) * std::size_t(keptColumns(link)));
    link.kernelEvaluations = counts.kernelEvaluations;
    link.rule = rule;
    link.computed = true;
    rays[k] = counts.raysCast;
  });
  for (std::size_t k = 0; k < todo.size(); ++k) {
    statistics_.kernelEvaluations += links_[std::size_t(todo[k])].kernelEvaluations;
    if (again[k]) {
      statistics_.recomputationEvaluations += links_[std::size_t(todo[k])].kernelEvaluations;
    }
    statistics_.integrationRays += rays[k];
    if (composites[k]) {
      statistics_.compositeEvaluations += links_[std::size_t(todo[k])].kernelEvaluations;
    }
  }
  statistics_.kernelEvaluations += statistics_.ruleCheckEvaluations - checksBefore;
  statistics_.couplingComputations += todo.size();
  statistics_.couplingSeconds +=
      std::chrono::duration<double>(chosen - start).count() +
      std::chrono::duration<double>(std::chrono::steady_clock::now() - stored).count();
}

void Solver::rebuildElementLinks() {
  for (std::size_t e = 0; e < hierarchy_->size(); ++e) (*hierarchy_)[int(e)].links.clear();
  for (std::size_t k = 0; k < links_.size(); ++k) {
    if (links_[k].active) (*hierarchy_)[links_[k].receiver].links.push_back(int(k));
  }
}

namespace {

// gathered += sum over the links of K times the source's B, with F known at compile time
// (Eigen::Dynamic for other sizes) so that the small products unroll into vector
// multiply-adds: a gather visits every link in every iteration. A link that keeps every
// column multiplies K (F x F) by B (F x 3); one that keeps the columns of its P source points
// multiplies them (F x P) by the source's projection Bhat (P x 3, source_projection.h), which
// reads and multiplies P / F of the coupling.
template <int F>
void gatherLinks(const std::vector<SolverLink>& links, const CouplingStore& couplings,
                 const Hierarchy& hierarchy, const std::vector<std::ptrdiff_t>& offsets,
                 const std::vector<double>& projections, Element& element) {
  const int functions = int(element.gathered.rows());
  const int orders = hierarchy.degree() + 1;
  using Matrix = Eigen::Matrix<double, F, F>;
  using Block = Eigen::Matrix<double, F, 3>;
  using Columns = Eigen::Matrix<double, F, Eigen::Dynamic>;
  using Projection = Eigen::Matrix<double, Eigen::Dynamic, 3>;
  Block sum = Block::Zero(functions, 3);
  const std::vector<int>& indices = element.links;
  for (std::size_t k = 0; k < indices.size(); ++k) {
    // The links' records and couplings lie apart in memory: fetch those of the links a few
    // places ahead while this one is multiplied.
    if (k + 8 < indices.size()) __builtin_prefetch(&links[std::size_t(indices[k + 8])]);
    if (k + 4 < indices.size()) {
      const SolverLink& ahead = links[std::size_t(indices[k + 4])];
      if (ahead.slot >= 0) {
        const char* start =
            reinterpret_cast<const char*>(couplings.data(keptColumns(ahead), ahead.slot));
        const std::size_t bytes =
            std::size_t(functions) * std::size_t(keptColumns(ahead)) * sizeof(double);
        for (std::size_t line = 0; line < bytes; line += 64) __builtin_prefetch(start + line);
      }
    }
    const SolverLink& link = links[std::size_t(indices[k])];
    if (!link.computed) continue;  // its source had no radiosity yet
    const double* coupling = couplings.data(keptColumns(link), link.slot);
    const int pu = link.gatherPoints[0], pv = link.gatherPoints[1];
    if (pu == orders && pv == orders) {
      sum.noalias() += Eigen::Map<const Matrix>(coupling, functions, functions)
                           .lazyProduct(Eigen::Map<const Block>(
                               hierarchy[link.source].radiosity.data(), functions, 3));
    } else {
      const std::ptrdiff_t offset =
          offsets[std::size_t(link.source) * std::size_t(functions) +
                  std::size_t((pu - 1) * orders + pv - 1)];
      sum.noalias() += Eigen::Map<const Columns>(coupling, functions, pu * pv)
                           .lazyProduct(Eigen::Map<const Projection>(
                               projections.data() + offset, pu * pv, 3));
    }
  }
  element.gathered = sum;
}

}  // namespace

// The projections Bhat of every (source, source points) pair some link gathers through
// (source_projection.h), from the sources' current radiosity.
void Solver::projectSources() {
  const int orders = options_.degree + 1;
  const std::size_t shapes = std::size_t(orders * orders);
  projectionOffset_.assign(hierarchy_->size() * shapes, -1);
  for (const SolverLink& link : links_) {
    if (!link.active || !link.computed) continue;
    const int pu = link.gatherPoints[0], pv = link.gatherPoints[1];
    if (pu == orders && pv == orders) continue;
    projectionOffset_[std::size_t(link.source) * shapes + std::size_t((pu - 1) * orders + pv - 1)] =
        0;
  }
  std::ptrdiff_t total = 0;
  for (std::size_t k = 0; k < projectionOffset_.size(); ++k) {
    if (projectionOffset_[k] < 0) continue;
    projectionOffset_[k] = total;
    const std::ptrdiff_t shape = std::ptrdiff_t(k % shapes);
    total += (shape / orders + 1) * (shape % orders + 1) * 3;
  }
  projections_.resize(std::size_t(total));
  tbb::parallel_for(std::size_t(0), hierarchy_->size(), [&](std::size_t e) {
    for (std::size_t shape = 0; shape < shapes; ++shape) {
      const std::ptrdiff_t offset = projectionOffset_[e * shapes + shape];
      if (offset < 0) continue;
      impl_->projection.project(int(shape) / orders + 1, int(shape) % orders + 1,
                                (*hierarchy_)[int(e)].radiosity.data(),
                                projections_.data() + offset);
    }
  });
}

// E_R = sum over R's links of K B_S (docs/design.md: E_a = sum_b K[a][b] B_b), with every
// source's radiosity from the previous iteration (Jacobi).
void Solver::gather() {
  projectSources();
  const int functions = hierarchy_->functions();
  const CouplingStore& couplings = impl_->couplings;
  tbb::parallel_for(std::size_t(0), hierarchy_->size(), [&](std::size_t e) {
    Element& element = (*hierarchy_)[int(e)];
    switch (functions) {
      case 1:
        return gatherLinks<1>(links_, couplings, *hierarchy_, projectionOffset_, projections_,
                              element);
      case 4:
        return gatherLinks<4>(links_, couplings, *hierarchy_, projectionOffset_, projections_,
                              element);
      case 9:
        return gatherLinks<9>(links_, couplings, *hierarchy_, projectionOffset_, projections_,
                              element);
      case 16:
        return gatherLinks<16>(links_, couplings, *hierarchy_, projectionOffset_, projections_,
                               element);
      default:
        return gatherLinks<Eigen::Dynamic>(links_, couplings, *hierarchy_, projectionOffset_,
                                           projections_, element);
    }
  });
}

// Returns the relative L2 change of the patch-level radiosity (the roots' coefficients are
// the projections of B on each patch's own basis; their Euclidean norm is the L2 norm of
// that projection over the surface).
double Solver::pushPull() {
  const std::size_t patches = scene_.patches.size();
  std::vector<double> change(patches), norm(patches);
  tbb::parallel_for(std::size_t(0), patches, [&](std::size_t p) {
    const Coefficients before = (*hierarchy_)[hierarchy_->root(int(p))].radiosity;
    hierarchy_->pushPull(int(p));
    const Coefficients& after = (*hierarchy_)[hierarchy_->root(int(p))].radiosity;
    change[p] = (after - before).squaredNorm();
    norm[p] = after.squaredNorm();
  });
  double totalChange = 0.0, totalNorm = 0.0;
  for (std::size_t p = 0; p < patches; ++p) {
    totalChange += change[p];
    totalNorm += norm[p];
  }
  return totalNorm > 0.0 ? std::sqrt(totalChange / totalNorm) : 0.0;
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
  double change = std::numeric_limits<double>::infinity();
  for (int iteration = 1; iteration <= options_.maxIterations; ++iteration) {
    const bool recheck = iteration == 1 || change < options_.tolerance;
    const bool refined = budgetExceeded_.empty() && recheck && refinementPass();
    if (!budgetExceeded_.empty()) {
      statistics_.failure = budgetExceeded_;
      break;
    }
    if (recheck && !refined && iteration > 1) {
      statistics_.converged = true;
      break;
    }
    rebuildElementLinks();
    computeCouplings();
    if (memoryExceeded("the coupling integration")) {
      statistics_.failure = budgetExceeded_;
      break;
    }
    gather();
    change = pushPull();
    statistics_.iterations = iteration;
    statistics_.finalChange = change;
    // With physical couplings (form factor sums <= 1) no radiosity exceeds the largest
    // emission over (1 - the largest reflectance); ten times that bound, or a value that is
    // not finite, is divergence.
    const std::string diverged = divergence();
    if (!diverged.empty()) {
      statistics_.failure = "diverged at iteration " + std::to_string(iteration) + ": " + diverged;
      break;
    }
    if (options_.progress) {
      std::size_t active = 0;
      for (const SolverLink& link : links_) active += link.active ? 1 : 0;
      options_.progress(SolveProgress{iteration, active, hierarchy_->size(),
                                      statistics_.kernelEvaluations, change, elapsed()});
    }
  }
  if (!statistics_.converged && statistics_.failure.empty()) {
    statistics_.failure = "no convergence within " + std::to_string(options_.maxIterations) +
                          " iterations (last relative change " +
                          std::to_string(statistics_.finalChange) + ")";
  }
  rebuildElementLinks();
  checkFormFactorSums();
  countLinks();
  statistics_.elapsedSeconds = elapsed();
  // The solution is in the hierarchy; the couplings (about 1 GiB for a cubic cornell solve)
  // are released so that a solver kept for its solution does not hold them.
  statistics_.couplingStoreBytes = impl_->couplings.bytes();
  impl_->couplings = CouplingStore(hierarchy_->functions());
  for (SolverLink& link : links_) link.slot = -1;
}

}  // namespace radquad
