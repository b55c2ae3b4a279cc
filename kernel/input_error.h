// Errors in what a user gave radquad (a file, an option, a rule name).
// Every command catches InputError at the top, prints its message on stderr and exits
// with status 2; internal invariants use assertions instead.
#pragma once

#include <stdexcept>
#include <string>

namespace radquad {

class InputError : public std::runtime_error {
 public:
  explicit InputError(const std::string& message) : std::runtime_error(message) {}
};

// Exit status of a command that rejected its input.
inline constexpr int kInputErrorExitStatus = 2;

}  // namespace radquad
