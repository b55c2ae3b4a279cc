// The study-config loader: JSON text -> StudyConfig (classes, rules, reference, gold,
// geometry ranges, scene-derived links) and back to JSON.
#include "experiments/json_input.h"
#include "experiments/study/study_config.h"
#include "tests/fuzz/fuzz_common.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace radquad;
  try {
    const StudyConfig config =
        parseStudyConfig(parseJsonText(fuzz::text(data, size), "fuzz"), "fuzz");
    (void)studyConfigToJson(config).dump();
  } catch (const InputError&) {
  }
  return 0;
}
