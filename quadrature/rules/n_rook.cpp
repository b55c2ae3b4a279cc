#include "quadrature/rules/n_rook.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "quadrature/random/philox.h"
#include "quadrature/random/seeds.h"

namespace radquad {

std::string NRookRule::citation() const {
  return "McKay, Beckman and Conover 1979 (Latin hypercube); Shirley 1991 (N-rooks); "
         "Gershbein 1995, section 3";
}

void NRookRule::drawSamples(std::uint64_t seed, RuleSamples& out) const {
  const std::size_t count = sampleCount();
  resizeEqualWeights(count, out);
  thread_local std::array<std::vector<std::uint32_t>, 4> permutations;
  thread_local std::vector<std::uint32_t> words;
  PhiloxStream stream(seed, randomStream(kFamily, 1));
  for (auto& permutation : permutations) stream.permutation(count, permutation);
  words.resize(8 * count);
  philoxBlocks(philoxKey(seed), randomStream(kFamily, 0), 0, 2 * count,
               words.data());
  const double width = 1.0 / double(count);
  const double below = std::nextafter(1.0, 0.0);
  auto place = [&](std::uint32_t stratum, std::uint32_t hi, std::uint32_t lo) {
    return std::min((double(stratum) + uniformFromWords(hi, lo)) * width, below);
  };
  LinkSamples& p = out.points;
  for (std::size_t k = 0; k < count; ++k) {
    const std::uint32_t* w = words.data() + 8 * k;
    p.s[k] = place(permutations[0][k], w[0], w[1]);
    p.t[k] = place(permutations[1][k], w[2], w[3]);
    p.u[k] = place(permutations[2][k], w[4], w[5]);
    p.v[k] = place(permutations[3][k], w[6], w[7]);
  }
}

std::shared_ptr<const Rule> makeNRookRule(const std::string& parameter) {
  return std::make_shared<NRookRule>(parseRuleParameter("NRook", parameter, 1, 10'000'000, "n"));
}

}  // namespace radquad
