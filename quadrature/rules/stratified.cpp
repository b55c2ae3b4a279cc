#include "quadrature/rules/stratified.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "quadrature/random/philox.h"

namespace radquad {

StratifiedRule::StratifiedRule(int strataPerAxis, std::string name)
    : strata_(strataPerAxis),
      name_(name.empty() ? "Stratified:" + std::to_string(strataPerAxis) : std::move(name)) {}

std::size_t StratifiedRule::sampleCount() const {
  const std::size_t k = std::size_t(strata_);
  return k * k * k * k;
}

std::string StratifiedRule::citation() const {
  return "Neyman 1934 (stratified sampling); Cook 1986 (jittering); Gershbein 1995, sections 3 "
         "and 4";
}

void StratifiedRule::drawSamples(std::uint64_t seed, RuleSamples& out) const {
  const std::size_t count = sampleCount();
  resizeEqualWeights(count, out);
  thread_local std::vector<std::uint32_t> words;
  words.resize(8 * count);
  philoxBlocks(philoxKey(seed), std::uint32_t(RandomStream::kStratified), 0, 2 * count,
               words.data());
  const int k = strata_;
  const double width = 1.0 / double(k);
  const double below = std::nextafter(1.0, 0.0);
  LinkSamples& p = out.points;
  std::size_t cell = 0;
  for (int is = 0; is < k; ++is) {
    for (int it = 0; it < k; ++it) {
      for (int iu = 0; iu < k; ++iu) {
        for (int iv = 0; iv < k; ++iv, ++cell) {
          const std::uint32_t* w = words.data() + 8 * cell;
          p.s[cell] = std::min((is + uniformFromWords(w[0], w[1])) * width, below);
          p.t[cell] = std::min((it + uniformFromWords(w[2], w[3])) * width, below);
          p.u[cell] = std::min((iu + uniformFromWords(w[4], w[5])) * width, below);
          p.v[cell] = std::min((iv + uniformFromWords(w[6], w[7])) * width, below);
        }
      }
    }
  }
}

std::shared_ptr<const Rule> makeStratifiedRule(const std::string& parameter) {
  return std::make_shared<StratifiedRule>(parseRuleParameter("Stratified", parameter, 1, 56, "k"));
}

}  // namespace radquad
