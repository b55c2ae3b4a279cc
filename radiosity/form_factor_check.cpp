// The solver's guard on its couplings' energy (radiosity/README.md, "Guards").
//
// Give every surface a radiosity of 1: the irradiance the couplings then deliver to a point is
// the sum, over the links whose receivers contain it (an element's own links and its
// ancestors', pushed down by the two-scale relations), of their point form factors as the
// links represent them. The true sum is the form factor from the point to everything it sees:
// at most 1. Its mean over a leaf element, the leaf's receiver sum U, is what the Jacobi
// iterations multiply a uniform radiosity by there, so a leaf with U > 1 receives energy that
// no surface sent, and 1 / (1 - rho U) amplifies the excess in bright scenes. U exceeds 1
// where couplings are integrated badly, and where a link accepted between large elements gives
// a small part of its receiver the mean of a form factor that varies across it: a ceiling
// right above a small occluder, or a floor beside a block, sees less of the room than the
// mean of the coarse links received by its ancestors says.
//
// Such a leaf is refined (Solver::solve, after the oracle has split what it wants): the links
// received by its ancestors are split at their receivers, so that the leaf's neighbourhood
// receives them itself, and its own links at their sources (else at the leaf) where the
// minimum area allows. A leaf that still exceeds the tolerance when nothing is left to split
// cannot be lowered by refinement: the solve fails, naming it.
#include <tbb/parallel_for.h>

#include <cmath>
#include <cstdio>

#include "radiosity/solver_impl.h"

namespace radquad {

std::vector<double> Solver::receiverSums() const {
  const std::size_t elements = hierarchy_->size();
  const int functions = hierarchy_->functions();
  // Per element, the coefficients of the irradiance its own links deliver from unit radiosity:
  // column 0 of K (the first kept column whatever the rule, since a source projection keeps a
  // constant exactly: source_projection.h) times the constant's coefficient sqrt(A_S).
  Eigen::MatrixXd sums = Eigen::MatrixXd::Zero(functions, Eigen::Index(elements));
  tbb::parallel_for(std::size_t(0), elements, [&](std::size_t e) {
    for (int index : (*hierarchy_)[int(e)].links) {
      const SolverLink& link = links_[std::size_t(index)];
      if (!link.coupling.computed || link.coupling.slot < 0) continue;
      const float* column = impl_->couplings.data(keptColumns(link), link.coupling.slot);
      const double constant = std::sqrt((*hierarchy_)[link.source].geometry.area);
      for (int a = 0; a < functions; ++a) sums(a, Eigen::Index(e)) += double(column[a]) * constant;
    }
  });
  // Pushed down (children come after their parents in the element array).
  const TwoScale& twoScale = hierarchy_->twoScale();
  for (std::size_t e = 0; e < elements; ++e) {
    const Element& element = (*hierarchy_)[int(e)];
    if (element.isLeaf()) continue;
    for (int c = 0; c < 4; ++c) {
      sums.col(element.firstChild + c).noalias() += twoScale.child(c) * sums.col(Eigen::Index(e));
    }
  }
  std::vector<double> mean(elements);
  for (std::size_t e = 0; e < elements; ++e) {
    mean[e] = sums(0, Eigen::Index(e)) / std::sqrt((*hierarchy_)[int(e)].geometry.area);
  }
  return mean;
}

std::size_t Solver::markSumViolations() {
  const std::vector<double> sums = receiverSums();
  forcedSplit_.assign(links_.size(), 0);
  std::vector<char> visited(hierarchy_->size(), 0);
  std::size_t marked = 0;
  for (std::size_t e = 0; e < sums.size(); ++e) {
    const Element& leaf = (*hierarchy_)[int(e)];
    if (!leaf.isLeaf() || sums[e] <= 1.0 + kFormFactorSumTolerance) continue;
    for (int a = leaf.parent; a >= 0 && !visited[std::size_t(a)]; a = (*hierarchy_)[a].parent) {
      visited[std::size_t(a)] = 1;
      for (int index : (*hierarchy_)[a].links) {
        if (!links_[std::size_t(index)].active) continue;
        forcedSplit_[std::size_t(index)] = kSplitReceiver;
        ++marked;
      }
    }
    // The leaf's own links: split where they still can be, the source first (a source seen
    // through fewer points than its kernel needs, a reduced adaptive rule's, is integrated
    // anew on each quarter), else the leaf.
    for (int index : leaf.links) {
      const SolverLink& link = links_[std::size_t(index)];
      if (!link.active) continue;
      const Element& source = (*hierarchy_)[link.source];
      const char side = splittable(source, minArea_)  ? kSplitSource
                        : splittable(leaf, minArea_) ? kSplitReceiver
                                                     : 0;
      if (side == 0) continue;
      forcedSplit_[std::size_t(index)] = side;
      ++marked;
    }
  }
  return marked;
}

void Solver::checkFormFactorSums() {
  const std::vector<double> sums = receiverSums();
  FormFactorSums& result = statistics_.formFactorSums;
  result = FormFactorSums{};
  for (std::size_t e = 0; e < sums.size(); ++e) {
    if (!(*hierarchy_)[int(e)].isLeaf()) continue;
    if (!(sums[e] <= result.maximum)) {
      result.maximum = sums[e];
      result.patch = (*hierarchy_)[int(e)].patch;
      result.element = int(e);
    }
    if (!(sums[e] <= 1.0 + kFormFactorSumTolerance)) ++result.violations;
  }
}

std::string Solver::describeElement(int e) const {
  const Element& element = (*hierarchy_)[e];
  char text[160];
  std::snprintf(text, sizeof text, " (its element at (u, v) = (%.4g, %.4g), side %.4g of the patch's)",
                element.u0, element.v0, element.size);
  return describePatch(scene_, std::size_t(element.patch)) + text;
}

}  // namespace radquad
