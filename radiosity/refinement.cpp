// The solver's links and their refinement: the initial links, their visibility classes, the
// BF oracle (with its estimate for links cut by a tangent plane) and the refinement passes
// that split links, including the choice of which element to split. The rest of the solver
// (rules, couplings, gathers, iterations) is in solver.cpp.
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <utility>

#include "kernel/progress_throttle.h"
#include "radiosity/link_integration.h"
#include "radiosity/solver_impl.h"
#include "reference/point_polygon_form_factor.h"

namespace radquad {

void Solver::createInitialLinks() {
  ProgressThrottle throttle;
  const int patches = int(scene_.patches.size());
  const auto report = [&](std::size_t patchesDone, std::size_t classified) {
    if (!options_.linkingProgress) return;
    if (const auto now = throttle.due()) {
      options_.linkingProgress(
          LinkingProgress{patchesDone, std::size_t(patches), links_.size(), classified, *now});
    }
  };
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
    // Quadratic in the patches: the budgets are checked, and progress reported, per row.
    if (links_.size() > options_.maxLinks) {
      budgetExceeded_ = "the link budget (" + std::to_string(options_.maxLinks) +
                        " links) was reached during the initial linking (patch " +
                        std::to_string(r + 1) + " of " + std::to_string(patches) +
                        "); raise --max-links, or merge patches";
      return;
    }
    if ((r % 16 == 15 || r + 1 == patches) && memoryExceeded("the initial linking")) return;
    report(std::size_t(r + 1), 0);
  }
  // Classification casts rays for every link: in chunks, with progress between them.
  constexpr std::size_t kChunk = std::size_t(1) << 16;
  HugePageVector<int> created;
  for (std::size_t begin = 0; begin < links_.size(); begin += kChunk) {
    const std::size_t end = std::min(links_.size(), begin + kChunk);
    created.resize(end - begin);
    for (std::size_t k = begin; k < end; ++k) created[k - begin] = int(k);
    classifyLinks(created);
    if (memoryExceeded("the initial links' classification")) return;
    report(std::size_t(patches), end);
  }
}

// Classifies the links in `created` whose parent was partial (or that are top-level):
// children of an unoccluded link are unoccluded (a sub-shaft lies inside the shaft). Marks
// every one of them that is near-field (link_integration.h).
void Solver::classifyLinks(HugePageVector<int>& created) {
  HugePageVector<std::uint64_t> rays(created.size(), 0);
  tbb::parallel_for(std::size_t(0), created.size(), [&](std::size_t k) {
    SolverLink& link = links_[std::size_t(created[k])];
    const Element& receiver = (*hierarchy_)[link.receiver];
    const Element& source = (*hierarchy_)[link.source];
    link.nearField = options_.nearField && nearField(receiver.geometry, source.geometry);
    if (link.visibility != LinkClass::kPartial) return;
    const bool topLevel = receiver.parent < 0 && source.parent < 0;
    Classification result =
        impl_->classifier.classify(receiver.geometry, receiver.patch, source.geometry, source.patch,
                                   topLevel ? nullptr : &link.candidates);
    link.visibility = result.visibility;
    link.occlusionProven = result.occlusionProven;
    link.candidates = std::move(result.candidates);
    rays[k] = result.raysCast;
    // Occluded links carry nothing; unless proven, they keep their candidates for a split.
    if (link.visibility == LinkClass::kOccluded) {
      link.active = false;
      if (link.occlusionProven) link.candidates.clear();
    }
  });
  for (std::uint64_t count : rays) statistics_.classificationRays += count;
}

namespace {

// The disc estimate of the form factors between two elements from one point of each,
//   F_RS ~ cos(theta_R) cos(theta_S) A_S / (pi r^2 + A_S)   (and F_SR with A_R),
// the larger of the two (cosines clamped at 0).
double discFormFactor(const Patch& receiver, const Eigen::Vector3d& x, const Patch& source,
                      const Eigen::Vector3d& y) {
  const Eigen::Vector3d d = y - x;
  const double r2 = d.squaredNorm();
  if (!(r2 > 0.0)) return 0.0;
  const double r = std::sqrt(r2);
  const double cosines =
      std::max(0.0, receiver.normal.dot(d) / r) * std::max(0.0, -source.normal.dot(d) / r);
  const double piR2 = std::numbers::pi * r2;
  return cosines *
         std::max(source.area / (piR2 + source.area), receiver.area / (piR2 + receiver.area));
}

}  // namespace

// The BF oracle (Hanrahan, Salzman and Aupperle 1991, section 4.2): the form factors between
// the elements, times the source's mean radiosity (largest channel); partial links are less
// certain. Elements apart (not near-field: link_integration.h) estimate them as those of a
// disc of the same area, from their centres. Near elements estimate them by the largest exact
// point form factor (Lambert's formula, the clamped cosines honoured: reference/
// point_polygon_form_factor.h) from the 3 x 3 points (corners, edge midpoints, centre) of each
// element to the other. From the centres alone such links were underestimated by orders of
// magnitude: a small receiver under a large source whose centre lies far off to one side (an
// 8 cm square 4 cm under a 3.7 x 5.3 m ceiling: 0.0007 for a form factor near 1), or a link
// cut by a tangent plane (a block face and the floor under it), whose centres may see nothing
// of each other; they were accepted coarse, and the receiver took the mean radiosity of a
// source far larger than the region it sees. Every part of an element in front of a plane
// that cuts it contains a corner, so the estimate is positive whenever the link can carry
// energy.
double Solver::oracleFormFactor(const SolverLink& link) const {
  const Element& receiver = (*hierarchy_)[link.receiver];
  const Element& source = (*hierarchy_)[link.source];
  const Element& larger = receiver.geometry.area >= source.geometry.area ? receiver : source;
  if (!splittable(larger, smallestArea(link))) return 0.0;
  const Patch& r = receiver.geometry;
  const Patch& s = source.geometry;
  if (!link.nearField) return discFormFactor(r, r.centre(), s, s.centre());
  double formFactor = 0.0;
  for (int a = 0; a < 9; ++a) {
    const double u = 0.5 * (a / 3), v = 0.5 * (a % 3);
    formFactor = std::max({formFactor, pointToPatchFormFactor(r.pointAt(u, v), r.normal, s),
                           pointToPatchFormFactor(s.pointAt(u, v), s.normal, r)});
  }
  return formFactor;
}

bool Solver::oracleSaysRefine(SolverLink& link) const {
  // Partial links are less certain; so are occluded ones, whose class rests on rays between
  // stratum centres that can miss a sliver of visibility: one whose estimate calls for a
  // split is split, and its children classified again.
  const double factor = link.visibility != LinkClass::kUnoccluded ? options_.partialFactor : 1.0;
  const double radiosity = std::max(0.0, (*hierarchy_)[link.source].meanRadiosity().maxCoeff());
  const double threshold = options_.bfEpsilon * radiosityScale_;
  // The form factor kept in single precision decides every link whose estimate lies clear of
  // the threshold (its rounding, below 1e-7 relative, cannot cross a margin of 1e-6); the
  // others, and a link's first examination, take the estimate in double precision, so the
  // decisions are those of the double-precision estimate everywhere.
  if (link.oracleFormFactor >= 0.0f) {
    const double estimate = double(link.oracleFormFactor) * radiosity * factor;
    if (estimate > threshold * (1.0 + 1e-6)) return true;
    if (estimate < threshold * (1.0 - 1e-6)) return false;
  }
  const double formFactor = oracleFormFactor(link);
  // Kept where single precision holds it to its relative rounding (0, or a normal float).
  const bool representable =
      formFactor == 0.0 || (formFactor >= double(std::numeric_limits<float>::min()) &&
                            formFactor <= double(std::numeric_limits<float>::max()));
  link.oracleFormFactor = representable ? float(formFactor) : -1.0f;
  return formFactor * radiosity * factor > threshold;
}

// The transfer alone accepts a link whose receiver is dim beside a source whose radiosity
// varies where the receiver looks: a block face 0.69 m from a red wall sees the strips of
// floor and ceiling along that wall, darker in blue than the polynomial of the large ceiling
// element the link reaches, and took their blue from the polynomial. The error such a link
// makes is at most F times the part of the source's radiosity that its polynomial cannot
// show (what its children hold beyond it), times the receiver's reflectance; it is weighed
// against the receiver's own radiosity (with a floor of the BF threshold, so that black
// receivers do not refine without end), channel by channel.
bool Solver::sourceVariationMatters(const SolverLink& link, double formFactor) const {
  if (!(options_.variationEpsilon > 0.0) || !link.active) return false;
  // Elements created in this pass are leaves when they are measured: nothing to show.
  if (std::size_t(link.source) >= sourceVariation_.size()) return false;
  const Element& source = (*hierarchy_)[link.source];
  if (source.isLeaf() || !splittable(source, smallestArea(link))) return false;
  const Element& receiver = (*hierarchy_)[link.receiver];
  const Eigen::Vector3d variation = sourceVariation_[std::size_t(link.source)].cast<double>();
  const Eigen::Vector3d own = receiver.meanRadiosity().cwiseMax(options_.bfEpsilon * radiosityScale_);
  const Eigen::Vector3d reflectance = scene_.patches[std::size_t(receiver.patch)].reflectance;
  const Eigen::Vector3d error = formFactor * reflectance.cwiseProduct(variation);
  return (error.array() > options_.variationEpsilon * own.array()).any();
}

int Solver::oracleChoice(SolverLink& link) const {
  if (oracleSaysRefine(link)) return splitSide(link);
  const double formFactor =
      link.oracleFormFactor >= 0.0f ? double(link.oracleFormFactor) : oracleFormFactor(link);
  return sourceVariationMatters(link, formFactor) ? 1 : -1;
}

void Solver::measureSourceVariation() {
  // With the test off, nothing reads the measure (sourceVariationMatters).
  if (!(options_.variationEpsilon > 0.0)) return;
  const std::size_t count = hierarchy_->size();
  sourceVariation_.assign(count, Eigen::Vector3f::Zero());
  const TwoScale& twoScale = hierarchy_->twoScale();
  tbb::parallel_for(std::size_t(0), count, [&](std::size_t e) {
    const Element& element = (*hierarchy_)[int(e)];
    if (element.isLeaf()) return;
    Eigen::Vector3d largest = Eigen::Vector3d::Zero();
    for (int c = 0; c < 4; ++c) {
      const Element& child = (*hierarchy_)[element.firstChild + c];
      const Coefficients residual = child.radiosity - twoScale.push(element.radiosity, c);
      // The orthonormal basis: the residual's RMS over the child is its norm over sqrt(A).
      largest = largest.cwiseMax(residual.colwise().norm().transpose() /
                                 std::sqrt(child.geometry.area));
    }
    sourceVariation_[e] = largest.cast<float>();
  });
}

// Elements closer than their size see each other's radiosity vary over distances of the gap
// between them, not of their own size: the office's cable tray 4 cm under the ceiling sees the
// strip of ceiling its own shadow darkens, and with elements of the default smallest area,
// wider than that gap, came out dark (radiosity/README.md). A near link whose elements face each
// other (normals within 60 degrees of opposite) across a gap narrower than the smallest
// element's side may split down to half the gap squared, and no further than a sixteenth of
// the smallest area (two more levels). Elements at an angle (a wall and the floor along their
// corner) keep the smallest area: the near field integrates their kernel's singularity.
double Solver::smallestArea(const SolverLink& link) const {
  if (!link.nearField) return minArea_;
  const Patch& receiver = (*hierarchy_)[link.receiver].geometry;
  const Patch& source = (*hierarchy_)[link.source].geometry;
  if (receiver.normal.dot(source.normal) > -0.5) return minArea_;
  const double gap = planeGap(receiver, source);
  if (!(gap > 0.0)) return minArea_;
  return std::clamp(0.5 * gap * gap, minArea_ / 16.0, minArea_);
}

// Splits every active link the oracle rejects into links to the larger element's children,
// breadth first: one wave of splits (sequential: it creates elements and links in a fixed
// order), then the new links' classification (parallel), then the next wave on them.
bool Solver::refinementPass() {
  // Active links, and occluded ones (carrying nothing) that the oracle may still split.
  auto examined = [](const SolverLink& link) {
    return link.active ||
           (link.visibility == LinkClass::kOccluded && !link.occlusionProven && !link.split);
  };
  HugePageVector<int> pending = linksWhere(links_, examined);
  measureSourceVariation();
  bool refined = false;
  ProgressThrottle throttle;
  int wave = 0;
  std::size_t splits = 0;
  const auto report = [&] {
    if (!options_.refinementProgress) return;
    if (const auto now = throttle.due()) {
      options_.refinementProgress(
          RefinementProgress{wave, splits, hierarchy_->size(), links_.size(), *now});
    }
  };
  while (!pending.empty()) {
    ++wave;
    if (memoryExceeded("refinement")) break;
    // Which links split, and which of their elements (a function of each link alone, so the
    // choices are made in parallel and applied in order).
    HugePageVector<int> choices(pending.size());
    tbb::parallel_for(std::size_t(0), pending.size(), [&](std::size_t k) {
      SolverLink& link = links_[std::size_t(pending[k])];
      // Links marked by the receiver-sum guard (form_factor_check.cpp) split at their
      // receivers; the others where the oracle says.
      const std::size_t index = std::size_t(pending[k]);
      if (wave == 1 && index < forcedSplit_.size() && forcedSplit_[index]) {
        choices[k] = forcedSplit_[index] == kSplitReceiver ? 0 : 1;
        return;
      }
      choices[k] = examined(link) ? oracleChoice(link) : -1;
    });
    HugePageVector<int> created;
    for (std::size_t k = 0; k < pending.size(); ++k) {
      if (choices[k] < 0) continue;
      if (hierarchy_->size() + 4 > options_.maxElements || links_.size() + 4 > options_.maxLinks) {
        budgetExceeded_ =
            hierarchy_->size() + 4 > options_.maxElements
                ? "the element budget (" + std::to_string(options_.maxElements) +
                      " elements) was reached during refinement"
                : "the link budget (" + std::to_string(options_.maxLinks) +
                      " links) was reached during refinement";
        budgetExceeded_ += "; raise --max-elements / --max-links, or refine less (a larger "
                           "--bf-eps or --min-area)";
        break;
      }
      // A wave can create millions of elements and links: the memory budget is checked, and
      // progress reported, within it too (before the next split, so every split is whole).
      if (splits % 4096 == 4095) {
        report();
        if (memoryExceeded("refinement")) break;
      }
      const int index = pending[k];
      SolverLink& parent = links_[std::size_t(index)];
      parent.active = false;
      parent.split = true;
      splitSinceListed_.push_back(index);
      parent.coupling.computed = false;
      if (parent.coupling.slot >= 0) {
        impl_->couplings.release(keptColumns(parent), std::exchange(parent.coupling.slot, -1));
      }
      const int receiver = parent.receiver, source = parent.source;
      const LinkClass visibility = parent.visibility;
      const std::vector<int> candidates = std::move(parent.candidates);
      parent.candidates.clear();
      ++statistics_.refinedLinks;
      ++splits;
      refined = true;
      const bool splitReceiver = choices[k] == 0;
      const int first = hierarchy_->subdivide(splitReceiver ? receiver : source);
      for (int c = 0; c < 4; ++c) {
        SolverLink link;
        link.receiver = splitReceiver ? first + c : receiver;
        link.source = splitReceiver ? source : first + c;
        if (!mayExchange((*hierarchy_)[link.receiver].geometry,
                         (*hierarchy_)[link.source].geometry)) {
          continue;
        }
        // Children of an occluded link are classified again, against its candidates.
        link.visibility = visibility == LinkClass::kOccluded ? LinkClass::kPartial : visibility;
        if (link.visibility == LinkClass::kPartial) link.candidates = candidates;
        links_.push_back(std::move(link));
        created.push_back(int(links_.size() - 1));
      }
    }
    classifyLinks(created);
    report();
    pending = std::move(created);
    if (!budgetExceeded_.empty()) break;
  }
  forcedSplit_.clear();
  return refined;
}

// Which element of a link the oracle wants refined is split: the larger one (the receiver on
// ties), unless the link is partially visible and its visibility changes across one element
// only, seen from the other's centre. That element holds the shadow boundary, which every
// link into it shares (a floor around a block's footprint, a wall around a window hung in
// front of it): splitting the larger element there would refine the sources again and again
// and leave the boundary inside one coarse receiver, whose polynomial then smears light into
// shadow (the slats scene's left wall converged 1.3% dark around its window).
// Returns 0 for the receiver, 1 for the source.
int Solver::splitSide(const SolverLink& link) const {
  const Patch& r = (*hierarchy_)[link.receiver].geometry;
  const Patch& s = (*hierarchy_)[link.source].geometry;
  const int larger = r.area >= s.area ? 0 : 1;
  if (link.visibility != LinkClass::kPartial) return larger;
  const VisibilityVariation variation = visibilityVariation(impl_->occluders, r, s);
  const int side = variation.receiver == variation.source ? larger : (variation.receiver ? 0 : 1);
  // The element must still be splittable; the oracle has checked that the larger one is.
  return (side == 0 ? r.area : s.area) > smallestArea(link) ? side : larger;
}

}  // namespace radquad
