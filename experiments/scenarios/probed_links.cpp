#include "experiments/scenarios/probed_links.h"

#include <algorithm>

#include "quadrature/random/seeds.h"
#include "quadrature/prepared_rule.h"
#include "quadrature/rules/gauss_product.h"

namespace radquad {

std::vector<ProbedLink> probedPartialLinks(std::uint64_t seed, const std::vector<OccluderKind>& kinds,
                                           int perKind) {
  const GeometryRanges ranges;
  const PreparedRule probe(std::make_shared<GaussProductRule>(GaussPointCounts{6, 6, 6, 6}), 0);
  CouplingAccumulator accumulator;
  std::vector<ProbedLink> links;
  std::vector<int> counts(kinds.size(), 0);
  for (std::uint64_t i = 0; i < 100000; ++i) {
    if (*std::min_element(counts.begin(), counts.end()) >= perKind) break;
    GeneratedLink generated = generateLink(ranges, StudyClass::partial, deriveSeed(seed, {1, i, 0}));
    const auto kind = std::size_t(std::find(kinds.begin(), kinds.end(), generated.occluderKind) -
                                  kinds.begin());
    if (kind == kinds.size() || counts[kind] >= perKind) continue;
    ProbedLink drawn{std::move(generated), nullptr};
    drawn.scene = drawn.generated.occluderScene();
    LinkIntegral probed;
    probe.integrate(drawn.link(), 0, accumulator, probed);
    const double visible = probed.visibleFraction();
    if (visible <= 0.05 || visible >= 0.95) continue;
    ++counts[kind];
    links.push_back(std::move(drawn));
  }
  return links;
}

}  // namespace radquad
