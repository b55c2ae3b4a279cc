#include "quadrature/rules/monte_carlo.h"

#include "quadrature/random/philox.h"
#include "quadrature/random/seeds.h"

namespace radquad {

std::string MonteCarloRule::citation() const {
  return "Metropolis and Ulam 1949; Cohen and Wallace 1993, section 4.9; Gershbein 1995, "
         "section 3";
}

void MonteCarloRule::drawSamples(std::uint64_t seed, RuleSamples& out) const {
  const std::size_t count = sampleCount();
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
