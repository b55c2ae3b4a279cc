// The subcommands of the `radquad` executable. Each registers itself on the top-level app;
// its callback throws InputError on bad input (main turns that into exit status 2).
#pragma once

#include <CLI/CLI.hpp>

namespace radquad {

void addLinkCommand(CLI::App& app);
void addReferenceCommand(CLI::App& app);
void addRulesCommand(CLI::App& app);
void addStudyCommand(CLI::App& app);
void addFiguresCommand(CLI::App& app);
void addSolveCommand(CLI::App& app);
void addAdaptiveCommand(CLI::App& app);
void addTraceCommand(CLI::App& app);

}  // namespace radquad
