#include "quadrature/random/random_rule.h"

#include <charconv>

#include "kernel/input_error.h"

namespace radquad {

void resizeEqualWeights(std::size_t count, RuleSamples& out) {
  out.isProduct = false;
  LinkSamples& points = out.points;
  points.s.resize(count);
  points.t.resize(count);
  points.u.resize(count);
  points.v.resize(count);
  points.weight.assign(count, 1.0 / double(count));
}

int parseRuleParameter(const std::string& family, const std::string& parameter, int minimum,
                       int maximum, const char* meaning) {
  int value = 0;
  const char* end = parameter.data() + parameter.size();
  const auto [next, error] = std::from_chars(parameter.data(), end, value);
  if (error != std::errc() || next != end || value < minimum || value > maximum) {
    throw InputError("rule " + family + ":" + parameter + ": expected " + family + ":" + meaning +
                     " with " + meaning + " an integer in " + std::to_string(minimum) + ".." +
                     std::to_string(maximum));
  }
  return value;
}

}  // namespace radquad
