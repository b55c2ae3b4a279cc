#include "quadrature/rule.h"

namespace radquad {

LinkSamples flattenedPoints(const RuleSamples& samples) {
  if (!samples.isProduct) return samples.points;
  LinkSamples out;
  for (std::size_t r = 0; r < samples.receiver.size(); ++r) {
    for (std::size_t q = 0; q < samples.source.size(); ++q) {
      out.push(samples.receiver.u[r], samples.receiver.v[r], samples.source.u[q],
               samples.source.v[q], samples.receiver.weight[r] * samples.source.weight[q]);
    }
  }
  return out;
}

std::string Rule::toString() const {
  std::string text = "Rule{" + name() + ", " + std::to_string(sampleCount()) + " samples, degree ";
  const auto declared = degree();
  text += declared ? std::to_string(*declared) : std::string("none");
  return text + ", " + family() + "}";
}

}  // namespace radquad
