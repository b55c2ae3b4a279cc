#include "radiosity/solver.h"

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "kernel/coupling.h"
#include "kernel/occluder_scene.h"
#include "radiosity/gauss_tables.h"
#include "radiosity/link_integration.h"

namespace radquad {

struct Solver::Impl {
  Impl(const Scene& scene, int degree) : tables(degree), classifier(scene, occluders) {
    for (const ScenePatch& patch : scene.patches) occluders.addParallelogram(patch.patch);
    occluders.commit();
  }
  OccluderScene occluders;  // every patch; a link's own patches never block it (DESIGN.md)
  GaussTables tables;
  VisibilityClassifier classifier;
  tbb::enumerable_thread_specific<CouplingAccumulator> accumulators;
};

Solver::Solver(const Scene& scene, SolverOptions options)
    : scene_(scene), options_(std::move(options)) {
  impl_ = std::make_unique<Impl>(scene, options_.degree);
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

void Solver::createInitialLinks() {
  const int patches = int(scene_.patches.size());
  for (int r = 0; r < patches; ++r) {
    for (int s = 0; s < patches; ++s) {
      if (r == s) continue;
      if (!mayExchange((*hierarchy_)[r].geometry, (*hierarchy_)[s].geometry)) continue;
      SolverLink link;
      link.receiver = hierarchy_->root(r);
      link.source = hierarchy_->root(s);
      link.visibility = LinkClass::kPartial;  // to be classified against every patch
      links_.push_back(std::move(link));
    }
  }
  std::vector<int> created(links_.size());
  for (std::size_t k = 0; k < created.size(); ++k) created[k] = int(k);
  classifyLinks(created);
}

// Classifies the links in `created` whose parent was partial (or that are top-level):
// children of an unoccluded link are unoccluded (a sub-shaft lies inside the shaft).
void Solver::classifyLinks(std::vector<int>& created) {
  std::vector<std::uint64_t> rays(created.size(), 0);
  tbb::parallel_for(std::size_t(0), created.size(), [&](std::size_t k) {
    SolverLink& link = links_[std::size_t(created[k])];
    if (link.visibility != LinkClass::kPartial) return;
    const Element& receiver = (*hierarchy_)[link.receiver];
    const Element& source = (*hierarchy_)[link.source];
    const bool topLevel = receiver.parent < 0 && source.parent < 0;
    Classification result =
        impl_->classifier.classify(receiver.geometry, receiver.patch, source.geometry, source.patch,
                                   topLevel ? nullptr : &link.candidates);
    link.visibility = result.visibility;
    link.candidates = std::move(result.candidates);
    rays[k] = result.raysCast;
    if (link.visibility == LinkClass::kOccluded) {
      link.active = false;  // occluded links carry nothing
      link.candidates.clear();
    }
  });
  for (std::uint64_t count : rays) statistics_.classificationRays += count;
}

// The BF oracle (Hanrahan, Salzman and Aupperle 1991, section 4.2): the form factors between
// the elements estimated from their centres as those of a disc of the same area,
//   F_RS ~ cos(theta_R) cos(theta_S) A_S / (pi r^2 + A_S)   (and F_SR with A_R),
// times the source's mean radiosity (largest channel); partial links are less certain.
bool Solver::oracleSaysRefine(const SolverLink& link) const {
  const Element& receiver = (*hierarchy_)[link.receiver];
  const Element& source = (*hierarchy_)[link.source];
  const Element& larger = receiver.geometry.area >= source.geometry.area ? receiver : source;
  if (larger.geometry.area <= minArea_ || larger.level >= options_.maxLevel) return false;
  const Eigen::Vector3d d = source.geometry.centre() - receiver.geometry.centre();
  const double r2 = d.squaredNorm();
  const double r = std::sqrt(r2);
  const double cosines = std::max(0.0, receiver.geometry.normal.dot(d) / r) *
                         std::max(0.0, -source.geometry.normal.dot(d) / r);
  const double piR2 = std::numbers::pi * r2;
  const double formFactor =
      cosines * std::max(source.geometry.area / (piR2 + source.geometry.area),
                         receiver.geometry.area / (piR2 + receiver.geometry.area));
  double estimate = formFactor * std::max(0.0, source.meanRadiosity().maxCoeff());
  if (link.visibility == LinkClass::kPartial) estimate *= options_.partialFactor;
  return estimate > options_.bfEpsilon * radiosityScale_;
}

// Splits every active link the oracle rejects into links to the larger element's children,
// breadth first: one wave of splits (sequential: it creates elements and links in a fixed
// order), then the new links' classification (parallel), then the next wave on them.
bool Solver::refinementPass() {
  std::vector<int> pending;
  for (std::size_t k = 0; k < links_.size(); ++k) {
    if (links_[k].active) pending.push_back(int(k));
  }
  bool refined = false;
  while (!pending.empty()) {
    std::vector<int> created;
    for (int index : pending) {
      if (!links_[std::size_t(index)].active) continue;
      if (!oracleSaysRefine(links_[std::size_t(index)])) continue;
      SolverLink& parent = links_[std::size_t(index)];
      parent.active = false;
      parent.computed = false;
      parent.coupling.resize(0, 0);
      const int receiver = parent.receiver, source = parent.source;
      const LinkClass visibility = parent.visibility;
      const std::vector<int> candidates = std::move(parent.candidates);
      parent.candidates.clear();
      ++statistics_.refinedLinks;
      refined = true;
      const bool splitReceiver =
          (*hierarchy_)[receiver].geometry.area >= (*hierarchy_)[source].geometry.area;
      const int first = hierarchy_->subdivide(splitReceiver ? receiver : source);
      for (int c = 0; c < 4; ++c) {
        SolverLink link;
        link.receiver = splitReceiver ? first + c : receiver;
        link.source = splitReceiver ? source : first + c;
        if (!mayExchange((*hierarchy_)[link.receiver].geometry,
                         (*hierarchy_)[link.source].geometry)) {
          continue;
        }
        link.visibility = visibility;
        if (visibility == LinkClass::kPartial) link.candidates = candidates;
        links_.push_back(std::move(link));
        created.push_back(int(links_.size() - 1));
      }
    }
    classifyLinks(created);
    pending = std::move(created);
  }
  return refined;
}

std::array<int, 4> Solver::chooseRule(const SolverLink&) const {
  switch (options_.rules) {
    case RuleChoice::kFixed:
      break;
  }
  const int n = options_.degree + 1;
  return {n, n, n, n};
}

void Solver::computeCouplings() {
  std::vector<int> todo;
  std::vector<std::array<int, 4>> rules;
  for (std::size_t k = 0; k < links_.size(); ++k) {
    const SolverLink& link = links_[k];
    if (!link.active) continue;
    const std::array<int, 4> rule = chooseRule(link);
    if (link.computed && rule == link.rule) continue;
    if (link.computed) ++statistics_.recomputations;
    todo.push_back(int(k));
    rules.push_back(rule);
  }
  std::vector<std::uint64_t> rays(todo.size(), 0);
  tbb::parallel_for(std::size_t(0), todo.size(), [&](std::size_t k) {
    SolverLink& link = links_[std::size_t(todo[k])];
    const std::array<int, 4>& rule = rules[k];
    const Link kernelLink{(*hierarchy_)[link.receiver].geometry,
                          (*hierarchy_)[link.source].geometry,
                          link.visibility == LinkClass::kPartial ? &impl_->occluders : nullptr};
    LinkIntegrationResult integral;
    integrateLink(kernelLink, rule, impl_->tables, hierarchy_->twoScale(), options_.singularDepth,
                  impl_->accumulators.local(), integral);
    link.coupling = std::move(integral.coupling);
    link.kernelEvaluations = integral.kernelEvaluations;
    link.rule = rule;
    link.computed = true;
    rays[k] = integral.raysCast;
  });
  for (std::size_t k = 0; k < todo.size(); ++k) {
    statistics_.kernelEvaluations += links_[std::size_t(todo[k])].kernelEvaluations;
    statistics_.integrationRays += rays[k];
  }
  statistics_.couplingComputations += todo.size();
}

void Solver::rebuildElementLinks() {
  for (std::size_t e = 0; e < hierarchy_->size(); ++e) (*hierarchy_)[int(e)].links.clear();
  for (std::size_t k = 0; k < links_.size(); ++k) {
    if (links_[k].active) (*hierarchy_)[links_[k].receiver].links.push_back(int(k));
  }
}

// E_R = sum over R's links of K B_S (DESIGN.md: E_a = sum_b K[a][b] B_b), with every
// source's radiosity from the previous iteration (Jacobi).
void Solver::gather() {
  tbb::parallel_for(std::size_t(0), hierarchy_->size(), [&](std::size_t e) {
    Element& element = (*hierarchy_)[int(e)];
    element.gathered.setZero();
    for (int index : element.links) {
      const SolverLink& link = links_[std::size_t(index)];
      element.gathered.noalias() += link.coupling * (*hierarchy_)[link.source].radiosity;
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
    if (link.visibility == LinkClass::kOccluded) {
      ++statistics_.occludedLinks;
    } else if (link.active) {
      ++(link.visibility == LinkClass::kUnoccluded ? statistics_.unoccludedLinks
                                                   : statistics_.partialLinks);
    }
  }
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
    const bool refined = recheck && refinementPass();
    if (recheck && !refined && iteration > 1) {
      statistics_.converged = true;
      break;
    }
    rebuildElementLinks();
    computeCouplings();
    gather();
    change = pushPull();
    statistics_.iterations = iteration;
    statistics_.finalChange = change;
    if (options_.progress) {
      std::size_t active = 0;
      for (const SolverLink& link : links_) active += link.active ? 1 : 0;
      options_.progress(SolveProgress{iteration, active, hierarchy_->size(),
                                      statistics_.kernelEvaluations, change, elapsed()});
    }
  }
  countLinks();
  statistics_.elapsedSeconds = elapsed();
}

}  // namespace radquad
