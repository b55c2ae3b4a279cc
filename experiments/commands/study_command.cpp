// `radquad study CONFIG.json --out FILE.json [--gold] [--quiet]`: scores the config's rules on
// its generated links and writes the error table of Figure 1 or 2 (README.md, "The study").
#include <memory>
#include <string>

#include "experiments/atomic_file.h"
#include "experiments/commands/commands.h"
#include "experiments/study/study_output.h"

namespace radquad {
namespace {

struct StudyCommandOptions {
  std::string configPath;
  std::string outPath;
  bool gold = false;
  bool quiet = false;
};

}  // namespace

void addStudyCommand(CLI::App& app) {
  auto options = std::make_shared<StudyCommandOptions>();
  CLI::App* command = app.add_subcommand(
      "study", "Score rules on a scenario suite against the reference; writes a JSON error table");
  command->add_option("config", options->configPath, "CONFIG.json (experiments/configs/)")
      ->required();
  command->add_option("--out", options->outPath, "Where to write the table (atomically)")
      ->required();
  command->add_flag("--gold", options->gold,
                    "Also score every rule and the reference against the gold reference");
  command->add_flag("--quiet", options->quiet, "No progress lines on stderr");
  command->callback([options] {
    checkOutputPath(options->outPath, "--out", {options->configPath});
    runStudyToFile(options->configPath, options->outPath,
                   StudyOptions{options->gold, !options->quiet});
  });
}

}  // namespace radquad
