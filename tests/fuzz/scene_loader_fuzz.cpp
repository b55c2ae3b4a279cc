// The scene loader: JSON text -> Scene (patches, reflectances, emissions, camera) and its
// validation.
#include "experiments/json_input.h"
#include "experiments/scene_input.h"
#include "tests/fuzz/fuzz_common.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace radquad;
  try {
    const Scene scene = parseScene(parseJsonText(fuzz::text(data, size), "fuzz"), "fuzz");
    (void)scene;
  } catch (const InputError&) {
  }
  return 0;
}
