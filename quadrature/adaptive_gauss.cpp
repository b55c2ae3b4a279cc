#include "quadrature/adaptive_gauss.h"

#include "kernel/input_error.h"
#include "quadrature/random/seeds.h"

#include <algorithm>
#include <cmath>

#include "quadrature/random/philox.h"

namespace radquad {

void axisMagnitudes(int degree, const double* magnitudes, double* alongU, double* alongV) {
  const int n = degree + 1;
  std::fill(alongU, alongU + n, 0.0);
  std::fill(alongV, alongV + n, 0.0);
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      const double magnitude = std::abs(magnitudes[i * n + j]);
      alongU[i] = std::max(alongU[i], magnitude);
      alongV[j] = std::max(alongV[j], magnitude);
    }
  }
}

int pointsForAxis(const double* orderMagnitudes, int orders, double errThres) {
  // Figure 4's loop: the last (highest) order above the threshold wins.
  int highest = 0;
  for (int order = 0; order < orders; ++order) {
    if (orderMagnitudes[order] > errThres) highest = order;
  }
  return highest + 1;
}

GaussPointCounts chooseGaussRulesNoVisibility(const AdaptiveGaussInput& input) {
  RADQUAD_REQUIRE(input.degree >= 0 && input.degree <= kMaxAdaptiveDegree);
  RADQUAD_REQUIRE(input.magnitudes != nullptr);
  double alongU[kMaxAdaptiveDegree + 1], alongV[kMaxAdaptiveDegree + 1];
  axisMagnitudes(input.degree, input.magnitudes, alongU, alongV);
  const int full = input.degree + 1;
  return {full, full, pointsForAxis(alongU, full, input.errThres),
          pointsForAxis(alongV, full, input.errThres)};
}

GaussPointCounts chooseGaussRules(const AdaptiveGaussInput& input, PhiloxStream& generator) {
  const GaussPointCounts rule = chooseGaussRulesNoVisibility(input);
  return input.partiallyOccluded ? increaseAnAxis(rule, input.degree, generator) : rule;
}

GaussPointCounts increaseAnAxis(GaussPointCounts rule, int degree, PhiloxStream& generator) {
  // "RandomlyIncreaseAnAxis(Src)": only an axis below the full d+1 points can grow.
  const int full = degree + 1;
  const bool uCanGrow = rule[2] < full, vCanGrow = rule[3] < full;
  if (uCanGrow && vCanGrow) {
    ++rule[generator.bounded(2) == 0 ? 2 : 3];
  } else if (uCanGrow) {
    ++rule[2];
  } else if (vCanGrow) {
    ++rule[3];
  }
  return rule;
}

std::uint64_t linkSeed(std::uint64_t baseSeed, std::uint32_t receiver, std::uint32_t source) {
  return deriveSeed(baseSeed, {receiver, source});
}

}  // namespace radquad
