#include "quadrature/rule.h"

namespace radquad {

std::string Rule::toString() const {
  std::string text = "Rule{" + name() + ", " + std::to_string(sampleCount()) + " samples, degree ";
  const auto declared = degree();
  text += declared ? std::to_string(*declared) : std::string("none");
  return text + ", " + family() + "}";
}

}  // namespace radquad
