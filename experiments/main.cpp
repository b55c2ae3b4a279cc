// radquad: quadrature of irradiance couplings in Galerkin radiosity.
#include <CLI/CLI.hpp>
#include <exception>
#include <iostream>

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
  } catch (const std::exception& error) {
    std::cerr << "radquad: internal error: " << error.what() << "\n";
    return 1;
  }
  return 0;
}
