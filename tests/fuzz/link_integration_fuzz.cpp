// A parsed link integrated by the product path (FullGauss) and the scattered and streamed
// paths (Stroud65, Stratified:4) at degrees 0 to 3 (the first byte): every legal link gives a
// finite coupling, or the computation is refused with an error; a non-finite result aborts.
#include <cmath>
#include <cstdlib>

#include "experiments/json_input.h"
#include "quadrature/prepared_rule.h"
#include "quadrature/registry.h"
#include "tests/fuzz/fuzz_common.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace radquad;
  if (size < 1) return 0;
  const int degree = data[0] % 4;
  try {
    const LinkGeometry description =
        parseLink(parseJsonText(fuzz::text(data + 1, size - 1), "fuzz"), "fuzz");
    const BuiltLink built = description.build();
    for (const char* name : {"FullGauss", "Stroud65", "Stratified:4"}) {
      const PreparedRule prepared(findRule(name), degree);
      const LinkIntegral integral = prepared.integrate(built.link, 7);
      if (!integral.coupling.allFinite() || !std::isfinite(integral.formFactor)) std::abort();
    }
  } catch (const InputError&) {
  } catch (const ComputationError&) {
  }
  return 0;
}
