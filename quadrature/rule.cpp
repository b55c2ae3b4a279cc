#include "quadrature/rule.h"

#include "kernel/input_error.h"

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

const RuleSamples& Rule::listedDraw(std::size_t trial) const {
  throw InputError("rule " + name() + " lists no draws (trial " + std::to_string(trial) + ")");
}

void checkDrawCount(const Rule& rule, int trials, const std::string& where) {
  const std::size_t count = rule.drawCount();
  if (count > 0 && std::size_t(trials) > count) {
    throw InputError(where + ": rule " + rule.name() + " lists " + std::to_string(count) +
                     (count == 1 ? " draw" : " draws") + " but " + std::to_string(trials) +
                     " trials are asked (trial t uses draw t)");
  }
}

std::string Rule::toString() const {
  std::string text = "Rule{" + name() + ", " + std::to_string(sampleCount()) + " samples, degree ";
  const auto declared = degree();
  text += declared ? std::to_string(*declared) : std::string("none");
  return text + ", " + family() + "}";
}

}  // namespace radquad
