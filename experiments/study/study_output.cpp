#include "experiments/study/study_output.h"

#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <iostream>

#include "experiments/atomic_file.h"
#include "experiments/rule_file.h"
#include "kernel/input_error.h"

#ifndef RADQUAD_SOURCE_DIR
#define RADQUAD_SOURCE_DIR "."
#endif
#ifndef RADQUAD_DATA_FROM_BIN
#define RADQUAD_DATA_FROM_BIN "../share/radquad"
#endif

extern char** environ;  // the process's environment, handed to the plot scripts

namespace radquad {
namespace {

std::string commandOutput(const std::string& command) {
  std::string text;
  FILE* pipe = popen(command.c_str(), "r");
  if (pipe == nullptr) return text;
  std::array<char, 256> buffer;
  while (fgets(buffer.data(), int(buffer.size()), pipe) != nullptr) text += buffer.data();
  pclose(pipe);
  while (!text.empty() && (text.back() == '\n' || text.back() == '\r')) text.pop_back();
  return text;
}

}  // namespace

std::filesystem::path dataRoot() {
  if (const char* folder = std::getenv("RADQUAD_DATA_DIR"); folder != nullptr && *folder) {
    return folder;
  }
  std::error_code error;
  const std::filesystem::path command = std::filesystem::read_symlink("/proc/self/exe", error);
  if (!error) {
    const std::filesystem::path installed = command.parent_path() / RADQUAD_DATA_FROM_BIN;
    if (std::filesystem::is_directory(installed / "experiments" / "configs", error)) {
      return installed.lexically_normal();
    }
  }
  return RADQUAD_SOURCE_DIR;
}

std::string gitCommit() {
  if (dataRoot() != std::filesystem::path(RADQUAD_SOURCE_DIR)) return "unknown";
  const std::string git = "git -C " + shellQuoted(std::string(RADQUAD_SOURCE_DIR)) + " ";
  const std::string head = commandOutput(git + "rev-parse HEAD 2>/dev/null");
  if (head.size() != 40) return "unknown";
  // The tables and figures a run writes do not count as changes to the code that made them.
  const std::string changes = commandOutput(
      git + "status --porcelain --untracked-files=no -- . ':!results' ':!plots' 2>/dev/null");
  return changes.empty() ? head : head + "-modified";
}

std::string shellQuoted(const std::string& text) {
  std::string out = "'";
  for (const char c : text) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

void checkPlotInterpreter(const std::string& python, const std::string& option) {
  const std::string command =
      shellQuoted(python) + " -c 'import matplotlib' >/dev/null 2>&1 </dev/null";
  if (std::system(command.c_str()) != 0) {
    throw InputError(option + " " + python +
                     ": cannot run it, or it has no matplotlib (the figures are plotted with it; "
                     "Debian: python3-matplotlib for /usr/bin/python3)");
  }
}

namespace {

// Waits for the child `pid` (again after an interrupted wait). Returns "" when it exited with
// status 0, else why not.
std::string waitForChild(int pid) {
  int status = 0;
  pid_t waited = -1;
  while ((waited = waitpid(pid, &status, 0)) < 0 && errno == EINTR) {
  }
  if (waited != pid) return std::string("cannot wait for it: ") + std::strerror(errno);
  return WIFEXITED(status) && WEXITSTATUS(status) == 0 ? "" : "failed";
}

}  // namespace

void runPlotScript(const std::string& python, const std::string& script,
                   const std::filesystem::path& results, const std::filesystem::path& plots,
                   const std::string& commandName, bool quiet) {
  BackgroundPlots plotting(python, script, results, plots, commandName, quiet);
  plotting.start({});
  plotting.finish();
}

BackgroundPlots::BackgroundPlots(std::string python, std::string script,
                                 std::filesystem::path results, std::filesystem::path plots,
                                 std::string commandName, bool quiet)
    : python_(std::move(python)),
      script_(std::move(script)),
      commandName_(std::move(commandName)),
      results_(std::move(results)),
      plots_(std::move(plots)),
      quiet_(quiet) {}

BackgroundPlots::~BackgroundPlots() {
  for (const Job& job : running_) waitForChild(job.pid);
}

void BackgroundPlots::start(const std::string& stem) {
  std::vector<std::string> words = {python_, (dataRoot() / "plots" / script_).string(),
                                    "--results", results_.string(), "--plots", plots_.string()};
  if (!stem.empty()) words.insert(words.end(), {"--only", stem});
  if (!quiet_) {
    std::string echoed;
    for (const std::string& word : words) {
      if (!echoed.empty()) echoed += ' ';
      echoed += shellQuoted(word);
    }
    std::cerr << "radquad " << commandName_ << ": " << echoed << "\n";
  }
  std::vector<char*> argv;
  for (const std::string& word : words) argv.push_back(const_cast<char*>(word.c_str()));
  argv.push_back(nullptr);
  pid_t pid = 0;
  const int error = posix_spawnp(&pid, python_.c_str(), nullptr, nullptr, argv.data(), ::environ);
  if (error != 0) {
    throw InputError("--python " + python_ + ": cannot start it for plots/" + script_ + ": " +
                     std::strerror(error));
  }
  running_.push_back({int(pid), stem});
}

void BackgroundPlots::finish() {
  std::string failed, why;
  for (const Job& job : running_) {
    const std::string outcome = waitForChild(job.pid);
    if (why.empty() && !outcome.empty()) {
      failed = job.stem;
      why = outcome;
    }
  }
  running_.clear();
  if (why.empty()) return;
  const std::string what =
      failed.empty() ? "" : " on " + (results_ / (failed + ".json")).string();
  throw InputError("plots/" + script_ + " failed" + what +
                   (why == "failed" ? " (is matplotlib installed for " + python_ + "?)"
                                    : ": " + why));
}

std::filesystem::path runRecordPath(const std::filesystem::path& result) {
  return result.parent_path() / (result.stem().string() + ".run.json");
}

nlohmann::json splitRunRecord(nlohmann::json& result, const std::vector<std::string>& keys) {
  if (result.is_object()) {
    nlohmann::json record = nlohmann::json::object();
    for (const std::string& key : keys) {
      if (result.contains(key)) {
        record[key] = std::move(result[key]);
        result.erase(key);
      }
    }
    for (auto& [key, value] : result.items()) {
      nlohmann::json inner = splitRunRecord(value, keys);
      if (!inner.is_null()) record[key] = std::move(inner);
    }
    return record.empty() ? nlohmann::json() : record;
  }
  if (result.is_array()) {
    nlohmann::json record = nlohmann::json::array();
    bool any = false;
    for (auto& value : result) {
      record.push_back(splitRunRecord(value, keys));
      any = any || !record.back().is_null();
    }
    return any ? record : nlohmann::json();
  }
  return nlohmann::json();
}

void writeRunRecord(const std::filesystem::path& result, nlohmann::json record) {
  if (record.is_null()) record = nlohmann::json::object();
  record["result"] = result.filename().string();
  record["git_commit"] = gitCommit();
  writeFileAtomically(runRecordPath(result), record.dump(2) + "\n");
}

nlohmann::json runStudyTable(const StudyConfig& config, const StudyOptions& options,
                             std::string* linkLines) {
  const StudyRun run = runStudy(config, options);
  if (linkLines != nullptr) *linkLines = linkTableLines(config, run);
  return studyTable(config, options, run);
}

StudyConfig readStudyConfigWith(const std::filesystem::path& configPath,
                                const StudyOverrides& overrides) {
  StudyConfig config = readStudyConfig(configPath);
  if (!overrides.rules.empty()) {
    for (const std::string& name : overrides.rules) findAnyRule(name);  // InputError if unknown
    config.rules = overrides.rules;
  }
  if (overrides.seed) config.seed = *overrides.seed;
  return config;
}

int unconvergedGolds(const nlohmann::json& table) {
  const auto gold = table.find("gold");
  if (gold == table.end()) return 0;
  return gold->value("unconverged_links", 0);
}

ComputationError unconvergedGoldError(const std::filesystem::path& table, int count) {
  return ComputationError(
      table.string() + ": the gold of " + std::to_string(count) +
      (count == 1 ? " link" : " links") +
      " did not reach its tolerance within its evaluation budget (the table is written, with "
      "gold.unconverged_links; --links-out lists each link's gold.converged): its scores "
      "are measured against a gold less accurate than asked");
}

nlohmann::json runStudyToFile(const StudyConfig& config, const std::filesystem::path& configPath,
                              const std::filesystem::path& outPath, const StudyOptions& options,
                              const std::filesystem::path& linksOutPath) {
  StudyOptions runOptions = options;
  runOptions.keepDetails = !linksOutPath.empty();
  std::string linkLines;
  const auto start = std::chrono::steady_clock::now();
  nlohmann::json table =
      runStudyTable(config, runOptions, linksOutPath.empty() ? nullptr : &linkLines);
  const double elapsed =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  // Relative to the source tree when inside it, so committed tables name no machine's paths.
  const auto absolute = std::filesystem::weakly_canonical(configPath);
  const auto relative =
      absolute.lexically_relative(std::filesystem::weakly_canonical(dataRoot()));
  const bool inside = !relative.empty() && *relative.begin() != "..";
  table["options"]["config_path"] = inside ? relative.string() : configPath.string();
  writeFileAtomically(outPath, table.dump(2) + "\n");
  writeRunRecord(outPath, {{"elapsed_seconds", elapsed}});
  if (!linksOutPath.empty()) writeFileAtomically(linksOutPath, linkLines);
  if (options.progress) {
    std::cerr << "radquad study: wrote " << outPath.string() << " in " << elapsed << " s\n";
  }
  return table;
}

}  // namespace radquad
