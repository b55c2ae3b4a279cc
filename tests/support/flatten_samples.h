// A product rule's points as a flat 4D list: every (receiver point, source point) pair with
// the product of their weights, in the product path's pair order (receiver-major).
#pragma once

#include "quadrature/rule.h"

namespace radquad::testing {

inline LinkSamples flattenSamples(const RuleSamples& samples) {
  if (!samples.isProduct) return samples.points;
  LinkSamples flat;
  for (std::size_t i = 0; i < samples.receiver.size(); ++i) {
    for (std::size_t j = 0; j < samples.source.size(); ++j) {
      flat.push(samples.receiver.u[i], samples.receiver.v[i], samples.source.u[j],
                samples.source.v[j], samples.receiver.weight[i] * samples.source.weight[j]);
    }
  }
  return flat;
}

}  // namespace radquad::testing
