// When a long computation reports its progress: once it has run a second, then at most once a
// second (the solver's initial linking, the exact gold). Not thread-safe: one reporting thread.
#pragma once

#include <chrono>
#include <optional>

namespace radquad {

class ProgressThrottle {
 public:
  // Seconds since construction when a report is due now, nothing otherwise.
  std::optional<double> due() {
    const double now =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    if (now < 1.0 || now - reported_ < 1.0) return std::nullopt;
    reported_ = now;
    return now;
  }

 private:
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
  double reported_ = 0.0;
};

}  // namespace radquad
