#include "experiments/commands/study_override_options.h"

#include <cstdint>

#include "experiments/trace_report.h"

namespace radquad {

void StudyOverrideOptions::addTo(CLI::App* command, const std::string& whose) {
  command->add_option("--rules", rules,
                      "Score these rules instead of " + whose +
                          " (comma-separated names, File:PATH included)")
      ->delimiter(',');
  command->add_option("--seed", seedText,
                      "Use this seed instead of " + whose + " (a decimal 0..2^64-1)");
  command->add_option("--threads", threads, "Worker threads (0: all cores)")
      ->check(CLI::Range(0, 4096))
      ->capture_default_str();
}

StudyOverrides StudyOverrideOptions::overrides() const {
  StudyOverrides out;
  out.rules = rules;
  if (!seedText.empty()) out.seed = parseDecimalOption(seedText, "--seed", 0, ~std::uint64_t(0));
  return out;
}

void StudyOverrideOptions::limitThreads(std::optional<tbb::global_control>& limit) const {
  if (threads > 0) {
    limit.emplace(tbb::global_control::max_allowed_parallelism, std::size_t(threads));
  }
}

}  // namespace radquad
