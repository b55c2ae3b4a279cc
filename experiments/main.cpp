// radquad: quadrature of irradiance couplings in Galerkin radiosity.
#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdlib>
#include <exception>
#include <iostream>
#include <string>

#include "experiments/commands/commands.h"
#include "experiments/version_info.h"
#include "kernel/input_error.h"

int main(int argc, char** argv) {
  CLI::App app{"radquad: quadrature of irradiance couplings in Galerkin radiosity"};
  app.require_subcommand(1);
  app.set_version_flag("--version", radquad::versionLine(),
                       "Print the version, the commit it was built from and the build flavour");
  radquad::addLinkCommand(app);
  radquad::addReferenceCommand(app);
  radquad::addRulesCommand(app);
  radquad::addStudyCommand(app);
  radquad::addFiguresCommand(app);
  radquad::addSolveCommand(app);
  radquad::addAdaptiveCommand(app);
  radquad::addTraceCommand(app);
  radquad::addBaselineCommand(app);
  radquad::addCheckCommand(app);
  // Checks every command's options share, before any command runs: a value option given an
  // empty value (`--out ""`, `--render ""`) is refused rather than read as absent, and a
  // number option (FLOAT) refuses inf and nan, which CLI11 would accept and range checks let
  // through (nan compares false).
  const CLI::Validator nonEmpty(
      [](std::string& value) { return value.empty() ? std::string("an empty value") : std::string(); },
      "", "NonEmpty");
  const CLI::Validator finite(
      [](std::string& value) {
        char* end = nullptr;
        const double number = std::strtod(value.c_str(), &end);
        if (end != value.c_str() && !std::isfinite(number)) return "not a finite number: " + value;
        return std::string();
      },
      "", "Finite");
  for (CLI::App* command : app.get_subcommands({})) {
    for (CLI::Option* option : command->get_options()) {
      if (option->get_type_size() == 0) continue;  // a flag
      option->check(nonEmpty);
      if (option->get_type_name().find("FLOAT") != std::string::npos) option->check(finite);
    }
  }
  // An unknown word where the command belongs is named (CLI11 would only say that a command
  // is required).
  if (argc > 1 && argv[1][0] != '-') {
    bool known = false;
    std::string names;
    for (const CLI::App* command : app.get_subcommands({})) {
      known = known || command->get_name() == argv[1];
      names += (names.empty() ? "" : ", ") + command->get_name();
    }
    if (!known) {
      std::cerr << "radquad: error: unknown command '" << argv[1] << "' (commands: " << names
                << ")\n";
      return radquad::kInputErrorExitStatus;
    }
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::Success& success) {
    return app.exit(success);
  } catch (const CLI::ParseError& error) {
    app.exit(error);
    return radquad::kInputErrorExitStatus;
  } catch (const radquad::InputError& error) {
    std::cerr << "radquad: error: " << error.what() << "\n";
    return radquad::kInputErrorExitStatus;
  } catch (const radquad::ComputationError& error) {
    std::cerr << "radquad: computation failed: " << error.what() << "\n";
    return radquad::kComputationErrorExitStatus;
  } catch (const radquad::CommandFailure& failure) {
    std::cerr << "radquad: " << failure.what() << "\n";
    return failure.status();
  } catch (const std::exception& error) {
    std::cerr << "radquad: internal error: " << error.what() << "\n";
    return 1;
  }
  return 0;
}
