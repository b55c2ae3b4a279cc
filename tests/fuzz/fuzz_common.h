// Shared by the libFuzzer harnesses (tests/fuzz/README.md): input errors are the expected
// outcome of most inputs; anything else escaping (another exception, a sanitizer report, a
// non-finite result, a crash) is a finding.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

#include "kernel/input_error.h"

namespace radquad::fuzz {

inline std::string text(const std::uint8_t* data, std::size_t size) {
  return std::string(reinterpret_cast<const char*>(data), size);
}

}  // namespace radquad::fuzz
