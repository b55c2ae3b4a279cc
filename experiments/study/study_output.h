// Running a study config to a finished table (the JSON of studyTable), written atomically,
// with its run record beside it (the commit and the elapsed time: what changes from run to
// run, kept out of the result so that regenerating it on an unchanged tree changes nothing).
#pragma once

#include <cstdint>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "experiments/study/study_runner.h"
#include "kernel/input_error.h"

namespace radquad {

// Where the commands find the files they read: experiments/configs/ (the figures' study
// configs) and plots/ (the plot scripts). In order: the folder RADQUAD_DATA_DIR names, when
// set; for an installed command (`cmake --install`), share/radquad beside its bin/ folder,
// wherever the installed tree was moved; otherwise the source tree it was built from.
std::filesystem::path dataRoot();

// `git rev-parse HEAD` of the source tree, with "-modified" appended when tracked files
// outside results/ and plots/ differ from it; "unknown" outside a repository and for an
// installed command (its data are not a checkout).
std::string gitCommit();

// `text` as one single-quoted word for the POSIX shell.
std::string shellQuoted(const std::string& text);

// Checked before any work: `python` (given as `option`) runs and imports matplotlib.
// InputError naming the option otherwise.
void checkPlotInterpreter(const std::string& python, const std::string& option);

// Runs `python plots/SCRIPT --results RESULTS --plots PLOTS` from the source tree and waits
// for it, echoed on stderr as "radquad COMMAND: ..." unless quiet. InputError when it fails.
void runPlotScript(const std::string& python, const std::string& script,
                   const std::filesystem::path& results, const std::filesystem::path& plots,
                   const std::string& commandName, bool quiet);

// A plot script drawing tables in the background, beside the computation that follows. The
// constructor starts `python plots/SCRIPT --results RESULTS --plots PLOTS --serve` (echoed on
// stderr as "radquad COMMAND: ..." unless quiet), which loads its libraries while the first
// table is computed and then reads table stems from its standard input, one a line, drawing
// each table's figures in turn and answering "drawn STEM" or "failed STEM" on its standard
// output (one socket carries both ways). start(stem) asks for a table without waiting;
// finish() ends the requests, waits for the script, and throws InputError naming the first
// table it did not draw. The destructor ends and waits likewise, without throwing (the script
// writes its outputs atomically).
class BackgroundPlots {
 public:
  BackgroundPlots(std::string python, std::string script, std::filesystem::path results,
                  std::filesystem::path plots, std::string commandName, bool quiet);
  BackgroundPlots(const BackgroundPlots&) = delete;
  BackgroundPlots& operator=(const BackgroundPlots&) = delete;
  ~BackgroundPlots();

  void start(const std::string& stem);
  void finish();

 private:
  // Closes the requests, reads the answers to the end, waits for the script: "" when every
  // table asked for was drawn and it exited with status 0; else the stem of the first table
  // not drawn (or "" if every one was), with `why` saying what went wrong.
  std::string close(std::string& why);

  std::string python_, script_, commandName_;
  std::filesystem::path results_;
  bool quiet_;
  int pid_ = -1;
  int socket_ = -1;  // this end of the script's standard input and output
  std::vector<std::string> requested_;
};

// The run record of a result file: in its folder, its stem + ".run.json" (results/fig1.json:
// results/fig1.run.json). .gitignore keeps run records out of the repository.
std::filesystem::path runRecordPath(const std::filesystem::path& result);

// Moves every member named in `keys` out of `result`, at any depth, into a record of the same
// shape (objects and arrays along the way), which it returns; what `result` keeps is then the
// same on every run.
nlohmann::json splitRunRecord(nlohmann::json& result, const std::vector<std::string>& keys);

// Writes `record` with "result" (the result's file name) and "git_commit" (gitCommit())
// added, atomically, to runRecordPath(result).
void writeRunRecord(const std::filesystem::path& result, nlohmann::json record);

// The table; with `linkLines`, the per-link table too (options.keepDetails must be set).
nlohmann::json runStudyTable(const StudyConfig& config, const StudyOptions& options,
                             std::string* linkLines = nullptr);

// What the command line may change in a config before it runs: the rule list and the seed.
struct StudyOverrides {
  std::vector<std::string> rules;     // empty: the config's
  std::optional<std::uint64_t> seed;  // none: the config's
};

// The config at `configPath` with `overrides` applied; the rules are looked up (InputError
// naming an unknown one) before anything is computed.
StudyConfig readStudyConfigWith(const std::filesystem::path& configPath,
                                const StudyOverrides& overrides);

// The links of `table` whose gold did not reach its tolerance (gold.unconverged_links; 0
// without a gold).
int unconvergedGolds(const nlohmann::json& table);

// The ComputationError of a table written with `count` unconverged golds: names the table.
ComputationError unconvergedGoldError(const std::filesystem::path& table, int count);

// Runs `config` (read from `configPath`, which the table records) and writes the table to
// `outPath` (atomically), its run record ({"elapsed_seconds"}, writeRunRecord) and, when
// `linksOutPath` is not empty, the per-link table there (atomically, after the table).
// Returns the table as written.
nlohmann::json runStudyToFile(const StudyConfig& config, const std::filesystem::path& configPath,
                              const std::filesystem::path& outPath, const StudyOptions& options,
                              const std::filesystem::path& linksOutPath = {});

}  // namespace radquad
