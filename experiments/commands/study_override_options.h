// The options `study` and `figures` share to change what their configs say: `--rules A,B`
// (File:PATH included), `--seed S` and `--threads T`.
#pragma once

#include <tbb/global_control.h>

#include <CLI/CLI.hpp>
#include <optional>
#include <string>
#include <vector>

#include "experiments/study/study_output.h"

namespace radquad {

struct StudyOverrideOptions {
  std::vector<std::string> rules;
  std::string seedText;
  int threads = 0;

  // Adds the three options to `command`; `whose` names what they replace ("the config's").
  void addTo(CLI::App* command, const std::string& whose);
  // The rules and the seed (InputError naming --seed when it is not a decimal 0..2^64-1).
  StudyOverrides overrides() const;
  // Limits the worker threads for as long as `limit` lives (nothing for --threads 0).
  void limitThreads(std::optional<tbb::global_control>& limit) const;
};

}  // namespace radquad
