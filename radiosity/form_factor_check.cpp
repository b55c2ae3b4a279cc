// The solver's check that its couplings are physical. A link's form factor is
// F = K[0][0] sqrt(A_S / A_R) (docs/design.md): the mean, over the receiver element, of the point
// form factor to the source element. For an element R, the links received by R and by its
// descendants carry energy from sources that do not overlap (a refinement replaces a link by
// links to the parts of one of its elements), so the area-weighted mean over R of their form
// factors is the mean over R of a point form factor to part of what R sees: at most 1 for
// exact couplings, whatever the refinement. The sum depends on the links' form factors only,
// not on how well the piecewise polynomials represent irradiance, so it measures quadrature
// error alone. A sum well above 1 means couplings that create energy; Jacobi iterations with
// them diverge once reflectances are high.
#include <tbb/parallel_for.h>

#include <cmath>

#include "radiosity/solver_impl.h"

namespace radquad {
namespace {

// The area-weighted mean over element e of its subtree's link form factors (children are
// quarters of their parent), recorded for every element of the subtree.
double sumUp(const Hierarchy& hierarchy, const std::vector<double>& own, int e,
             std::vector<double>& sums) {
  const Element& element = hierarchy[e];
  double total = own[std::size_t(e)];
  if (!element.isLeaf()) {
    for (int c = 0; c < 4; ++c) total += 0.25 * sumUp(hierarchy, own, element.firstChild + c, sums);
  }
  sums[std::size_t(e)] = total;
  return total;
}

}  // namespace

void Solver::checkFormFactorSums() {
  const std::size_t elements = hierarchy_->size();
  std::vector<double> own(elements, 0.0);
  tbb::parallel_for(std::size_t(0), elements, [&](std::size_t e) {
    const double receiverArea = (*hierarchy_)[int(e)].geometry.area;
    for (int index : (*hierarchy_)[int(e)].links) {
      const SolverLink& link = links_[std::size_t(index)];
      if (!link.coupling.computed || link.coupling.slot < 0) continue;
      // K[0][0]: the first entry of the kept columns (column 0 is always kept).
      const double k00 = impl_->couplings.data(keptColumns(link), link.coupling.slot)[0];
      own[e] += k00 * std::sqrt((*hierarchy_)[link.source].geometry.area / receiverArea);
    }
  });
  std::vector<double> sums(elements, 0.0);
  tbb::parallel_for(std::size_t(0), scene_.patches.size(), [&](std::size_t p) {
    sumUp(*hierarchy_, own, hierarchy_->root(int(p)), sums);
  });
  FormFactorSums& result = statistics_.formFactorSums;
  result = FormFactorSums{};
  for (std::size_t e = 0; e < elements; ++e) {
    if (!(sums[e] <= result.maximum)) {
      result.maximum = sums[e];
      result.patch = (*hierarchy_)[int(e)].patch;
    }
    if (!(sums[e] <= 1.0 + kFormFactorSumTolerance)) ++result.violations;
  }
}

}  // namespace radquad
