#include "experiments/study/study_output.h"

#include <spawn.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <stdexcept>

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

std::vector<std::string> scriptWords(const std::string& python, const std::string& script,
                                     const std::filesystem::path& results,
                                     const std::filesystem::path& plots) {
  return {python, (dataRoot() / "plots" / script).string(), "--results", results.string(),
          "--plots", plots.string()};
}

void echo(const std::string& commandName, const std::vector<std::string>& words) {
  std::string echoed;
  for (const std::string& word : words) {
    if (!echoed.empty()) echoed += ' ';
    echoed += shellQuoted(word);
  }
  std::cerr << "radquad " << commandName << ": " << echoed << "\n";
}

// Starts `words` (words[0] looked up on PATH); with standardIo >= 0, that descriptor becomes
// the child's standard input and output.
int spawn(const std::vector<std::string>& words, const std::string& script, int standardIo) {
  std::vector<char*> argv;
  for (const std::string& word : words) argv.push_back(const_cast<char*>(word.c_str()));
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  if (standardIo >= 0) {
    posix_spawn_file_actions_adddup2(&actions, standardIo, 0);
    posix_spawn_file_actions_adddup2(&actions, standardIo, 1);
  }
  pid_t pid = 0;
  const int error = posix_spawnp(&pid, words[0].c_str(), &actions, nullptr, argv.data(), ::environ);
  posix_spawn_file_actions_destroy(&actions);
  if (error != 0) {
    throw InputError("--python " + words[0] + ": cannot start it for plots/" + script + ": " +
                     std::strerror(error));
  }
  return int(pid);
}

std::string matplotlibHint(const std::string& python) {
  return " (is matplotlib installed for " + python + "?)";
}

}  // namespace

void runPlotScript(const std::string& python, const std::string& script,
                   const std::filesystem::path& results, const std::filesystem::path& plots,
                   const std::string& commandName, bool quiet) {
  const std::vector<std::string> words = scriptWords(python, script, results, plots);
  if (!quiet) echo(commandName, words);
  const std::string why = waitForChild(spawn(words, script, -1));
  if (why.empty()) return;
  throw InputError("plots/" + script + " failed" +
                   (why == "failed" ? matplotlibHint(python) : ": " + why));
}

BackgroundPlots::BackgroundPlots(std::string python, std::string script,
                                 std::filesystem::path results, std::filesystem::path plots,
                                 std::string commandName, bool quiet)
    : script_(std::move(script)),
      commandName_(std::move(commandName)),
      results_(std::move(results)),
      quiet_(quiet) {
  int ends[2];
  if (socketpair(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0, ends) != 0) {
    throw std::runtime_error(std::string("cannot connect to plots/") + script_ + ": " +
                             std::strerror(errno));
  }
  std::vector<std::string> words = scriptWords(python, script_, results_, plots);
  words.push_back("--serve");
  if (!quiet_) echo(commandName_, words);
  try {
    pid_ = spawn(words, script_, ends[1]);
  } catch (...) {
    ::close(ends[0]);
    ::close(ends[1]);
    throw;
  }
  ::close(ends[1]);
  socket_ = ends[0];
  python_ = std::move(python);
}

BackgroundPlots::~BackgroundPlots() {
  std::string why;
  if (pid_ >= 0) close(why);
}

void BackgroundPlots::start(const std::string& stem) {
  requested_.push_back(stem);
  if (!quiet_) {
    std::cerr << "radquad " << commandName_ << ": plotting " << (results_ / (stem + ".json")).string()
              << "\n";
  }
  const std::string line = stem + "\n";
  std::size_t sent = 0;
  while (sent < line.size()) {
    // A script that has stopped reading (it failed) is found out by finish().
    const ssize_t written = send(socket_, line.data() + sent, line.size() - sent, MSG_NOSIGNAL);
    if (written < 0 && errno == EINTR) continue;
    if (written <= 0) return;
    sent += std::size_t(written);
  }
}

std::string BackgroundPlots::close(std::string& why) {
  shutdown(socket_, SHUT_WR);
  std::string answers;
  char buffer[4096];
  for (;;) {
    const ssize_t got = read(socket_, buffer, sizeof buffer);
    if (got < 0 && errno == EINTR) continue;
    if (got <= 0) break;
    answers.append(buffer, std::size_t(got));
  }
  ::close(socket_);
  socket_ = -1;
  why = waitForChild(pid_);
  pid_ = -1;
  std::vector<std::string> drawn;
  std::size_t begin = 0;
  while (begin < answers.size()) {
    std::size_t end = answers.find('\n', begin);
    if (end == std::string::npos) end = answers.size();
    const std::string answer = answers.substr(begin, end - begin);
    begin = end + 1;
    if (answer.rfind("drawn ", 0) == 0) drawn.push_back(answer.substr(6));
    if (answer.rfind("failed ", 0) == 0) {
      if (why.empty()) why = "failed";
      return answer.substr(7);
    }
  }
  for (const std::string& stem : requested_) {
    if (std::find(drawn.begin(), drawn.end(), stem) == drawn.end()) {
      if (why.empty()) why = "it ended without drawing it";
      if (why == "failed" && drawn.empty()) why = "nothing drawn";
      return stem;
    }
  }
  return "";
}

void BackgroundPlots::finish() {
  std::string why;
  const std::string failed = close(why);
  if (why.empty()) return;
  const std::string what = failed.empty() ? "" : " on " + (results_ / (failed + ".json")).string();
  throw InputError("plots/" + script_ + " failed" + what +
                   (why == "nothing drawn" ? matplotlibHint(python_)
                    : why == "failed"      ? ""
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
    // Scene links refused for an unconverged gold (each replaced by the next candidate of its
    // class; the tables' candidates.refused_unconverged_gold).
    const auto refusals = [&](const std::string& name, const nlohmann::json& candidates) {
      const int refused = candidates.value("refused_unconverged_gold", 0);
      if (refused > 0) {
        std::cerr << "radquad study: " << name << ": " << refused
                  << " scene link(s) refused, their gold unconverged (candidates "
                  << candidates["refused_gold_candidates"].dump()
                  << "), each replaced by the next candidate of the class\n";
      }
    };
    if (table.contains("classes")) {
      for (const auto& [name, classTable] : table["classes"].items()) {
        refusals(name, classTable["candidates"]);
      }
    } else {
      refusals("partial", table["candidates"]);
    }
    std::cerr << "radquad study: wrote " << outPath.string() << " in " << elapsed << " s\n";
  }
  return table;
}

}  // namespace radquad
