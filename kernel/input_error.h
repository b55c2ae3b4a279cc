// Errors in what a user gave radquad (a file, an option, a rule name), and computations that
// failed. Every command catches InputError at the top, prints its message on stderr and exits
// with status 2 (ComputationError: status 3). Internal invariants are checked in every build
// with RADQUAD_REQUIRE, which throws std::logic_error naming the condition and its place.
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

// A computation that failed on valid input: a non-finite result, or an iteration that did
// not converge. Commands print the message on stderr and exit with status 3; no result file
// is written.
class ComputationError : public std::runtime_error {
 public:
  explicit ComputationError(const std::string& message) : std::runtime_error(message) {}
};

inline constexpr int kComputationErrorExitStatus = 3;

// An internal invariant that does not hold: a bug, never bad input.
[[noreturn]] inline void requireFailed(const char* condition, const char* file, int line) {
  throw std::logic_error(std::string("internal check failed: ") + condition + " (" + file + ":" +
                         std::to_string(line) + ")");
}

}  // namespace radquad

// Checks an internal invariant in every build (unlike assert, which release builds drop).
#define RADQUAD_REQUIRE(condition) \
  ((condition) ? void(0) : ::radquad::requireFailed(#condition, __FILE__, __LINE__))
