// The rule-name parser: "FullGauss", "Gauss:4x4x4x4", "Stratified:12", "File:...", ...
// A name it accepts must give a usable rule: its sample count and samples are computed.
#include <cstdlib>

#include "quadrature/registry.h"
#include "tests/fuzz/fuzz_common.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace radquad;
  if (size > 256) return 0;
  try {
    const auto rule = findRule(fuzz::text(data, size));
    // Large rules are legal; sampling them is not what this harness is for.
    if (rule->sampleCount() <= 100000) {
      const RuleSamples samples = rule->samples(1);
      (void)samples;
    }
  } catch (const InputError&) {
  }
  return 0;
}
