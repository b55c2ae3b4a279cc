// The solver's state that its header keeps private, shared by its phases (solver.cpp,
// refinement.cpp, rule_choice.cpp, gather.cpp and the checks in form_factor_check.cpp): the
// occluder scene of every patch, the Gauss tables, the visibility classifier, per-thread link
// integrators and the coupling store.
#pragma once

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <Eigen/Core>

#include <algorithm>
#include <cstdint>
#include <vector>

#include "kernel/occluder_scene.h"
#include "radiosity/coupling_store.h"
#include "radiosity/gauss_tables.h"
#include "radiosity/link_integration.h"
#include "radiosity/near_field.h"
#include "radiosity/solver.h"
#include "radiosity/source_projection.h"

namespace radquad {

// One link as the gather reads it (16 bytes, where its record takes 88).
struct GatherEntry {
  const float* coupling;     // its kept columns in the coupling store
  int source;                // the source element
  std::uint8_t pointsU = 0;  // the source points its columns belong to (gatherPoints)
  std::uint8_t pointsV = 0;
};

struct Solver::Impl {
  Impl(const Scene& scene, int degree, DroppedOrders dropped)
      : tables(degree),
        classifier(scene, occluders),
        couplings((degree + 1) * (degree + 1)),
        projection(degree, dropped) {
    for (const ScenePatch& patch : scene.patches) occluders.addParallelogram(patch.patch);
    occluders.commit();
  }
  OccluderScene occluders;  // every patch; a link's own patches never block it (docs/design.md)
  GaussTables tables;
  VisibilityClassifier classifier;
  tbb::enumerable_thread_specific<LinkIntegrator> integrators;
  tbb::enumerable_thread_specific<NearFieldIntegrator> nearField;
  CouplingStore couplings;  // each link's kept columns of K (rows receiver functions)
  SourceProjection projection;
  tbb::enumerable_thread_specific<Eigen::MatrixXd> scratch;  // a link's whole K
  // What the gather reads of each link, receiver by receiver (gather.cpp): the links of
  // element e are gatherEntries[gatherBegin[e] .. gatherBegin[e + 1]), in the order of its
  // list of links. Built again whenever links or their couplings change (refinement, or a
  // coupling pass that integrated some link); otherwise the iterations reuse it.
  HugePageVector<GatherEntry> gatherEntries;
  std::vector<std::size_t> gatherBegin;
  bool gatherCurrent = false;
};

// The indices of the links for which `pick(link)` holds, in link order: the links are scanned
// in parallel, block by block (a scan over millions of links otherwise takes a core's tens of
// milliseconds, in every pass).
template <typename Pick>
HugePageVector<int> linksWhere(const LinkArray& links, const Pick& pick) {
  constexpr std::size_t kBlock = std::size_t(1) << 14;
  std::vector<std::vector<int>> found((links.size() + kBlock - 1) / kBlock);
  tbb::parallel_for(std::size_t(0), found.size(), [&](std::size_t block) {
    const std::size_t end = std::min(links.size(), (block + 1) * kBlock);
    for (std::size_t k = block * kBlock; k < end; ++k) {
      if (pick(links[k])) found[block].push_back(int(k));
    }
  });
  std::size_t total = 0;
  for (const std::vector<int>& block : found) total += block.size();
  HugePageVector<int> indices;
  indices.reserve(total);
  for (const std::vector<int>& block : found) indices.insert(indices.end(), block.begin(), block.end());
  return indices;
}

}  // namespace radquad
