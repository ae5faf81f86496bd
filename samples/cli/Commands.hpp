#pragma once
// Each command family of the `coulomb` CLI registers its subcommands on the app (main.cpp).
// A command's callback throws CommandError (message, exit status) on bad input; main prints it.
#include <CLI/CLI.hpp>

#include <stdexcept>
#include <string>

namespace coulomb::cli {

struct CommandError : std::runtime_error {
  explicit CommandError(const std::string& message, int status = 1)
      : std::runtime_error(message), exitStatus(status) {}
  int exitStatus;
};

void registerSceneCommands(CLI::App& app);       // run, scenes          (SceneCommands.cpp)
void registerSolverCommands(CLI::App& app);      // solve, solvers       (SolverCommands.cpp)
void registerUrdfCommands(CLI::App& app);        // urdf info, dynamics  (UrdfCommands.cpp)
void registerCompareCommand(CLI::App& app);      // compare              (CompareCommand.cpp)
void registerBenchCommand(CLI::App& app);        // bench                (BenchCommand.cpp)
void registerConformanceCommand(CLI::App& app);  // conformance    (ConformanceCommand.cpp)
void registerViewCommands(CLI::App& app);        // view, render         (ViewCommands.cpp)

}  // namespace coulomb::cli
