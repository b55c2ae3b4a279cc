// The subcommands of the `radquad` executable. Each registers itself on the top-level app;
// its callback throws InputError on bad input (main turns that into exit status 2).
#pragma once

#include <CLI/CLI.hpp>
#include <stdexcept>
#include <string>

namespace radquad {

// Thrown by a command whose own checks failed (its input was fine and its work done): main
// prints the message and exits with `status` (radquad check: 1).
class CommandFailure : public std::runtime_error {
 public:
  CommandFailure(const std::string& message, int status)
      : std::runtime_error(message), status_(status) {}
  int status() const { return status_; }

 private:
  int status_;
};

void addLinkCommand(CLI::App& app);
void addReferenceCommand(CLI::App& app);
void addRulesCommand(CLI::App& app);
void addStudyCommand(CLI::App& app);
void addFiguresCommand(CLI::App& app);
void addSolveCommand(CLI::App& app);
void addAdaptiveCommand(CLI::App& app);
void addTraceCommand(CLI::App& app);
void addBaselineCommand(CLI::App& app);
void addCheckCommand(CLI::App& app);

}  // namespace radquad
