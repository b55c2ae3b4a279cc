#include "quadrature/rules/monte_carlo.h"

#include <vector>

#include "quadrature/random/philox.h"

namespace radquad {

MonteCarloRule::MonteCarloRule(int count, std::string name)
    : count_(count),
      name_(name.empty() ? "MonteCarlo:" + std::to_string(count) : std::move(name)) {}

std::string MonteCarloRule::citation() const {
  return "Metropolis and Ulam 1949; Cohen and Wallace 1993, section 4.9; Gershbein 1995, "
         "section 3";
}

void MonteCarloRule::drawSamples(std::uint64_t seed, RuleSamples& out) const {
  const std::size_t count = std::size_t(count_);
  resizeEqualWeights(count, out);
  thread_local std::vector<std::uint32_t> words;
  words.resize(8 * count);
  philoxBlocks(philoxKey(seed), std::uint32_t(RandomStream::kMonteCarlo), 0, 2 * count,
               words.data());
  LinkSamples& p = out.points;
  for (std::size_t k = 0; k < count; ++k) {
    const std::uint32_t* w = words.data() + 8 * k;
    p.s[k] = uniformFromWords(w[0], w[1]);
    p.t[k] = uniformFromWords(w[2], w[3]);
    p.u[k] = uniformFromWords(w[4], w[5]);
    p.v[k] = uniformFromWords(w[6], w[7]);
  }
}

std::shared_ptr<const Rule> makeMonteCarloRule(const std::string& parameter) {
  return std::make_shared<MonteCarloRule>(
      parseRuleParameter("MonteCarlo", parameter, 1, 10'000'000, "n"));
}

}  // namespace radquad
