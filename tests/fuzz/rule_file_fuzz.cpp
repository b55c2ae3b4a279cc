// The rule-file loader (File:PATH): JSON text -> a data rule (strict keys, point shapes,
// finite values in [0, 1], weights summing to 1, the declared degree's exactness check) ->
// its points integrated on a fixed link; a non-finite coupling from a rule that loaded
// aborts.
#include <cmath>
#include <cstdlib>

#include "experiments/json_input.h"
#include "experiments/rule_file.h"
#include "quadrature/prepared_rule.h"
#include "tests/fuzz/fuzz_common.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace radquad;
  static const Patch receiver =
      Patch::make({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, "receiver");
  static const Patch source = Patch::make({0, 1, 1}, {1, 0, 0}, {0, -1, 0}, "source");
  try {
    const auto rule = parseRuleJson(parseJsonText(fuzz::text(data, size), "fuzz"), "fuzz");
    if (rule->sampleCount() > 100000) return 0;  // the loader accepts any size; keep runs fast
    const LinkIntegral integral = PreparedRule(rule, 1).integrate(Link{receiver, source, nullptr});
    if (!integral.coupling.allFinite()) std::abort();
  } catch (const InputError&) {
  }
  return 0;
}
