// Gauss-Legendre product rules on [0,1]^4.
//
// Citation: the tensor product of one-dimensional Gauss-Legendre rules (C. F. Gauss 1814;
// nodes and weights as in Abramowitz and Stegun, "Handbook of Mathematical Functions", 1964,
// 25.4.29), as used for Galerkin radiosity couplings by Zatz (1993) and Troutman and Max (1993).
//
// Parameters (the name `Gauss:RsxRtxSuxSv`):
//   Rs, Rt  points along the receiver's edge_u and edge_v (1..64)
//   Su, Sv  points along the source's edge_u and edge_v (1..64)
// Samples: Rs Rt Su Sv. Degree: min over the axes of 2n - 1 (total degree).
// Named forms (Gershbein 1995, section 3): FullGauss = 3x3x3x3, LinSrcGauss = 3x3x2x2,
// ConstSrcGauss = 3x3x1x1.
#pragma once

#include <array>
#include <memory>
#include <string>

#include "quadrature/gauss_legendre.h"
#include "quadrature/rule.h"

namespace radquad {

class GaussProductRule : public Rule {
 public:
  // `name` empty: the canonical "Gauss:RsxRtxSuxSv".
  GaussProductRule(GaussPointCounts pointsPerAxis, std::string name = "");

  std::string name() const override { return name_; }
  std::size_t sampleCount() const override;
  std::optional<int> degree() const override;
  std::string family() const override { return "Gauss-Legendre product"; }
  std::string citation() const override;
  RuleSamples samples(std::uint64_t seed) const override;

  const GaussPointCounts& pointsPerAxis() const { return pointsPerAxis_; }

 private:
  GaussPointCounts pointsPerAxis_;
  std::string name_;
  RuleSamples samples_;
};

// Parses the parameter of `Gauss:RsxRtxSuxSv` (the text after the colon).
std::shared_ptr<const Rule> makeGaussProductRule(const std::string& parameter);

// The product of the receiver's and the source's 2D Gauss rules (the adaptive method uses it).
std::string gaussProductName(const GaussPointCounts& pointsPerAxis);

}  // namespace radquad
