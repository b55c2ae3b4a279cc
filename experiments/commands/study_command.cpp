// `radquad study CONFIG.json --out FILE.json [--links-out FILE.jsonl] [--no-gold] [--rules A,B]
// [--seed S] [--threads T] [--quiet]`: scores the config's rules on
// its generated links and writes the error table of Figure 1 or 2 (docs/study.md).
#include <tbb/global_control.h>

#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "experiments/atomic_file.h"
#include "experiments/commands/commands.h"
#include "experiments/commands/study_override_options.h"
#include "experiments/study/study_output.h"
#include "kernel/input_error.h"

namespace radquad {
namespace {

struct StudyCommandOptions {
  std::string configPath;
  std::string outPath;
  std::string linksOutPath;
  bool gold = true;
  bool quiet = false;
  StudyOverrideOptions overrides;
};

}  // namespace

void addStudyCommand(CLI::App& app) {
  auto options = std::make_shared<StudyCommandOptions>();
  CLI::App* command = app.add_subcommand(
      "study", "Score rules on a scenario suite against the gold and the paper's reference; writes a JSON error table");
  command->add_option("config", options->configPath, "CONFIG.json (experiments/configs/)")
      ->required();
  command->add_option("--out", options->outPath, "Where to write the table (atomically)")
      ->required();
  command->add_option("--links-out", options->linksOutPath,
                      "Also write the per-link table: one JSON object per line, with the link's "
                      "geometry and every coupling (atomically)");
  command->add_flag("--gold,!--no-gold", options->gold,
                    "Score every rule and the paper's reference against the gold reference "
                    "(the default; --no-gold: against the paper's reference only)");
  command->add_flag("--quiet", options->quiet, "No progress lines on stderr");
  options->overrides.addTo(command, "the config's");
  command->callback([options] {
    const StudyOverrides overrides = options->overrides.overrides();
    checkOutputPath(options->outPath, "--out", {options->configPath});
    if (!options->linksOutPath.empty()) {
      checkOutputPath(options->linksOutPath, "--links-out", {options->configPath});
      if (std::filesystem::weakly_canonical(options->linksOutPath) ==
          std::filesystem::weakly_canonical(options->outPath)) {
        throw InputError("--links-out " + options->linksOutPath + ": is also --out");
      }
    }
    StudyOptions study;
    study.gold = options->gold;
    study.progress = !options->quiet;
    std::optional<tbb::global_control> threadLimit;
    options->overrides.limitThreads(threadLimit);
    const nlohmann::json table =
        runStudyToFile(readStudyConfigWith(options->configPath, overrides), options->configPath,
                       options->outPath, study, options->linksOutPath);
    // The table stays written (complete, the golds that fell short marked), but the run
    // failed: status 3.
    if (const int unconverged = unconvergedGolds(table); unconverged > 0) {
      throw unconvergedGoldError(options->outPath, unconverged);
    }
  });
}

}  // namespace radquad
