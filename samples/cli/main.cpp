// coulomb: the command-line front end (docs/architecture.md section 0).
#include <iostream>

#include "Commands.hpp"

int main(int argc, char** argv) {
  CLI::App app{"coulomb: rigid-body physics with exact Coulomb friction"};
  app.require_subcommand(1);
  coulomb::cli::registerSceneCommands(app);
  coulomb::cli::registerSolverCommands(app);
  coulomb::cli::registerUrdfCommands(app);
  coulomb::cli::registerCompareCommand(app);
  coulomb::cli::registerBenchCommand(app);
  coulomb::cli::registerConformanceCommand(app);
  coulomb::cli::registerViewCommands(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  } catch (const coulomb::cli::CommandError& e) {
    std::cerr << "coulomb: " << e.what() << "\n";
    return e.exitStatus;
  } catch (const std::exception& e) {
    std::cerr << "coulomb: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
