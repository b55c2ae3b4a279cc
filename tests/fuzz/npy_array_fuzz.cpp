// The .npy member parser of NumPy archives (File:PATH.npz rules): bytes -> an array, or an
// InputError; never a read outside the bytes, whatever the header claims. A parsed array's
// values must number what its shape says.
#include <cstdlib>
#include <string>

#include "experiments/npz_input.h"
#include "kernel/input_error.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace radquad;
  try {
    const NpyArray array =
        parseNpy(std::string(reinterpret_cast<const char*>(data), size), "fuzz.npz: a");
    const std::size_t values = array.isString ? array.strings.size() : array.numbers.size();
    if (values != array.size()) std::abort();
  } catch (const InputError&) {
  }
  return 0;
}
