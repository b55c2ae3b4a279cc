#include "quadrature/rules/gauss_product.h"

#include <algorithm>
#include <charconv>

#include "kernel/input_error.h"
#include "quadrature/gauss_legendre.h"

namespace radquad {
std::string gaussProductName(const GaussPointCounts& pointsPerAxis) {
  return "Gauss:" + std::to_string(pointsPerAxis[0]) + "x" + std::to_string(pointsPerAxis[1]) +
         "x" + std::to_string(pointsPerAxis[2]) + "x" + std::to_string(pointsPerAxis[3]);
}

GaussProductRule::GaussProductRule(GaussPointCounts pointsPerAxis, std::string name)
    : pointsPerAxis_(pointsPerAxis),
      name_(name.empty() ? gaussProductName(pointsPerAxis) : std::move(name)) {
  for (int n : pointsPerAxis_) {
    if (n < 1 || n > kMaxGaussPoints) {
      throw InputError("rule " + name_ + ": each axis needs 1.." + std::to_string(kMaxGaussPoints) +
                       " points");
    }
  }
  samples_.isProduct = true;
  samples_.receiver = gaussProductSamples(pointsPerAxis_[0], pointsPerAxis_[1]);
  samples_.source = gaussProductSamples(pointsPerAxis_[2], pointsPerAxis_[3]);
}

std::size_t GaussProductRule::sampleCount() const {
  std::size_t count = 1;
  for (int n : pointsPerAxis_) count *= std::size_t(n);
  return count;
}

std::optional<int> GaussProductRule::degree() const {
  return 2 * *std::min_element(pointsPerAxis_.begin(), pointsPerAxis_.end()) - 1;
}

std::string GaussProductRule::citation() const {
  return "Tensor product of Gauss-Legendre rules (Abramowitz and Stegun 1964, 25.4.29); "
         "Gershbein 1995, section 3";
}

RuleSamples GaussProductRule::samples(std::uint64_t) const {
  return samples_;
}

std::shared_ptr<const Rule> makeGaussProductRule(const std::string& parameter) {
  GaussPointCounts counts{};
  const char* cursor = parameter.data();
  const char* end = parameter.data() + parameter.size();
  for (int axis = 0; axis < 4; ++axis) {
    const auto [next, error] = std::from_chars(cursor, end, counts[axis]);
    const bool separatorOk = axis == 3 ? next == end : (next != end && *next == 'x');
    if (error != std::errc() || !separatorOk) {
      throw InputError("rule Gauss:" + parameter +
                       ": expected Gauss:RsxRtxSuxSv with four point counts, e.g. Gauss:3x3x2x2");
    }
    cursor = next + 1;
  }
  return std::make_shared<GaussProductRule>(counts);
}

}  // namespace radquad
