// radquad: quadrature of irradiance couplings in Galerkin radiosity.
#include <CLI/CLI.hpp>
#include <exception>
#include <iostream>
#include <string>

#include "experiments/commands/commands.h"
#include "kernel/input_error.h"

int main(int argc, char** argv) {
  CLI::App app{"radquad: quadrature of irradiance couplings in Galerkin radiosity"};
  app.require_subcommand(1);
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
