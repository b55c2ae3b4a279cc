// The solver's gather (the Jacobi step E_R = sum over R's links of K B_S) and the source
// projections it reads; solver.cpp calls it once per iteration.
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cstring>

#include "radiosity/coupling_store.h"
#include "radiosity/solver.h"
#include "radiosity/solver_impl.h"

namespace radquad {

namespace {

// gathered += sum over the links of K times the source's B, with F known at compile time
// (Eigen::Dynamic for other sizes) so that the small products unroll into vector
// multiply-adds: a gather visits every link in every iteration. A link that keeps every
// column multiplies K (F x F) by B (F x 3); one that keeps the columns of its P source points
// multiplies them (F x P) by the source's projection Bhat (P x 3, source_projection.h), which
// reads and multiplies P / F of the coupling. The links come from the gather table (16 bytes
// each, in the order they are read) rather than from the link records (88 bytes each, spread
// over the whole array).
template <int F>
void gatherLinks(const GatherEntry* entries, std::size_t count,
                 const Hierarchy& hierarchy, const std::vector<std::ptrdiff_t>& offsets,
                 const std::vector<double>& projections, Element& element) {
  const int functions = int(element.gathered.rows());
  const int orders = hierarchy.degree() + 1;
  using Matrix = Eigen::Matrix<float, F, F>;
  using Block = Eigen::Matrix<double, F, 3>;
  using Columns = Eigen::Matrix<float, F, Eigen::Dynamic>;
  using Projection = Eigen::Matrix<double, Eigen::Dynamic, 3>;
  Block sum = Block::Zero(functions, 3);
  for (std::size_t k = 0; k < count; ++k) {
    // The couplings lie apart in memory: fetch those of the links a few places ahead while
    // this one is multiplied.
    if (k + 4 < count) {
      const GatherEntry& ahead = entries[k + 4];
      const char* start = reinterpret_cast<const char*>(ahead.coupling);
      const std::size_t bytes =
          std::size_t(functions) * std::size_t(ahead.pointsU * ahead.pointsV) * sizeof(float);
      for (std::size_t line = 0; line < bytes; line += 64) __builtin_prefetch(start + line);
    }
    const GatherEntry& entry = entries[k];
    const int pu = entry.pointsU, pv = entry.pointsV;
    if (pu == orders && pv == orders) {
      sum.noalias() += Eigen::Map<const Matrix>(entry.coupling, functions, functions)
                           .template cast<double>()
                           .lazyProduct(Eigen::Map<const Block>(
                               hierarchy[entry.source].radiosity.data(), functions, 3));
    } else {
      const std::ptrdiff_t offset =
          offsets[std::size_t(entry.source) * std::size_t(functions) +
                  std::size_t((pu - 1) * orders + pv - 1)];
      sum.noalias() += Eigen::Map<const Columns>(entry.coupling, functions, pu * pv)
                           .template cast<double>()
                           .lazyProduct(Eigen::Map<const Projection>(
                               projections.data() + offset, pu * pv, 3));
    }
  }
  element.gathered = sum;
}

}  // namespace

// Where the projections Bhat of every (source, source points) pair some link gathers through
// go (source_projection.h): laid out again whenever the gather table is, since only the
// links' creation, splits and couplings change which pairs are gathered through.
void Solver::layOutProjections() {
  const int orders = options_.degree + 1;
  const std::size_t shapes = std::size_t(orders * orders);
  projectionOffset_.assign(hierarchy_->size() * shapes, -1);
  const auto gathersThroughProjection = [orders](const SolverLink& link) {
    return link.active && link.coupling.computed &&
           !(link.coupling.gatherPoints[0] == orders && link.coupling.gatherPoints[1] == orders);
  };
  for (const int k : linksWhere(links_, gathersThroughProjection)) {
    const SolverLink& link = links_[std::size_t(k)];
    const int pu = link.coupling.gatherPoints[0], pv = link.coupling.gatherPoints[1];
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
}

// The projections, from the sources' current radiosity.
void Solver::projectSources() {
  const int orders = options_.degree + 1;
  const std::size_t shapes = std::size_t(orders * orders);
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
  if (!impl_->gatherCurrent) {
    layOutProjections();
    buildGatherTable();
  }
  projectSources();
  const int functions = hierarchy_->functions();
  const Impl& impl = *impl_;
  tbb::parallel_for(std::size_t(0), hierarchy_->size(), [&](std::size_t e) {
    Element& element = (*hierarchy_)[int(e)];
    const GatherEntry* entries = impl.gatherEntries.data() + impl.gatherBegin[e];
    const std::size_t count = impl.gatherBegin[e + 1] - impl.gatherBegin[e];
    switch (functions) {
      case 1:
        return gatherLinks<1>(entries, count, *hierarchy_, projectionOffset_, projections_, element);
      case 4:
        return gatherLinks<4>(entries, count, *hierarchy_, projectionOffset_, projections_, element);
      case 9:
        return gatherLinks<9>(entries, count, *hierarchy_, projectionOffset_, projections_, element);
      case 16:
        return gatherLinks<16>(entries, count, *hierarchy_, projectionOffset_, projections_,
                               element);
      default:
        return gatherLinks<Eigen::Dynamic>(entries, count, *hierarchy_, projectionOffset_,
                                           projections_, element);
    }
  });
}

// The gather table from the elements' lists of active links: every link whose coupling is
// computed (one whose source had no radiosity yet is left out, as it carries nothing).
void Solver::buildGatherTable() {
  const std::size_t elements = hierarchy_->size();
  impl_->gatherBegin.assign(elements + 1, 0);
  tbb::parallel_for(std::size_t(0), elements, [&](std::size_t e) {
    std::size_t computed = 0;
    for (int index : (*hierarchy_)[int(e)].links) {
      computed += links_[std::size_t(index)].coupling.computed ? 1 : 0;
    }
    impl_->gatherBegin[e + 1] = computed;
  });
  for (std::size_t e = 0; e < elements; ++e) impl_->gatherBegin[e + 1] += impl_->gatherBegin[e];
  impl_->gatherEntries.resize(impl_->gatherBegin[elements]);
  tbb::parallel_for(std::size_t(0), elements, [&](std::size_t e) {
    std::size_t k = impl_->gatherBegin[e];
    for (int index : (*hierarchy_)[int(e)].links) {
      const SolverLink& link = links_[std::size_t(index)];
      if (!link.coupling.computed) continue;
      impl_->gatherEntries[k++] = GatherEntry{
          impl_->couplings.data(keptColumns(link), link.coupling.slot), link.source,
          std::uint8_t(link.coupling.gatherPoints[0]), std::uint8_t(link.coupling.gatherPoints[1])};
    }
  });
  impl_->gatherCurrent = true;
}

}  // namespace radquad
