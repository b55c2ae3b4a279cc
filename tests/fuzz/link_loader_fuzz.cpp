// The link loader: JSON text -> LinkGeometry (strict keys, lengths, finite numbers,
// non-degenerate patches, interpenetration) -> an Embree occluder scene.
#include "experiments/json_input.h"
#include "tests/fuzz/fuzz_common.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace radquad;
  try {
    const LinkGeometry description = parseLink(parseJsonText(fuzz::text(data, size), "fuzz"), "fuzz");
    const BuiltLink built = description.build();
    (void)built;
  } catch (const InputError&) {
  }
  return 0;
}
