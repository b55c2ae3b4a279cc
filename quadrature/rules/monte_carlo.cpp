#include "quadrature/rules/monte_carlo.h"

#include "quadrature/random/philox.h"
#include "quadrature/random/seeds.h"

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
  LinkSamples& p = out.points;
  philoxUniformQuads(philoxKey(seed), randomStream(kFamily, 0), 0, count,
                     p.s.data(), p.t.data(), p.u.data(), p.v.data());
}

std::shared_ptr<const Rule> makeMonteCarloRule(const std::string& parameter) {
  return std::make_shared<MonteCarloRule>(
      parseRuleParameter("MonteCarlo", parameter, 1, 10'000'000, "n"));
}

}  // namespace radquad
