// `coulomb compare SCENE [--solvers a,b,...] [--steps N] [--dt S]`: the scene once per solver,
// one row each (SolverComparison.hpp says what every column means).
#include <iostream>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "Commands.hpp"
#include "SceneRun.hpp"
#include "SolverComparison.hpp"

namespace coulomb::cli {
namespace {

struct CompareOptions {
  std::string scene;
  std::string solvers = "auto,pgs,bgs,ac_newton";
  SceneOverrides overrides;
  double timeCap = std::numeric_limits<double>::infinity();
};

void compare(const CompareOptions& options) {
  const std::vector<std::string> solvers = splitList(options.solvers);
  if (solvers.empty()) throw CommandError("--solvers: give at least one solver name");
  std::vector<engine::io::Scene> scenes;  // every scene is built first: bad names fail fast
  for (const std::string& solver : solvers) {
    SceneOverrides overrides = options.overrides;
    overrides.solver = solver;
    scenes.push_back(loadScene(options.scene, overrides));
    buildWorldFor(scenes.back());  // checks the solver name (the message names it)
  }
  const engine::io::Scene& first = scenes.front();
  std::cout << "compare " << first.name << " (" << first.source << "): " << first.bodies.size()
            << " bodies, " << first.steps << " steps of " << first.settings.timeStep
            << " s; tolerance " << first.settings.solve.options.tolerance << ", max iterations "
            << first.settings.solve.options.maxIterations << " (0 = solver default)\n";
  printComparisonHeader(std::cout);
  for (const engine::io::Scene& scene : scenes)
    printComparisonRow(std::cout, runForComparison(scene, options.timeCap));
}

}  // namespace

void registerCompareCommand(CLI::App& app) {
  auto options = std::make_shared<CompareOptions>();
  CLI::App* command = app.add_subcommand(
      "compare",
      "Run a scene once per solver and print one row each: ms/step (median), iterations, "
      "common residual, max penetration, max drift, energy change, fallbacks");
  command->add_option("scene", options->scene, "Built-in scene name or path to a .json scene")
      ->required();
  command
      ->add_option("--solvers", options->solvers,
                   "Comma-separated solvers (auto, names of `coulomb solvers`, NAME! for no "
                   "fallback)")
      ->capture_default_str();
  command->add_option("--steps", options->overrides.steps, "Number of steps (default: the scene's)")
      ->check(CLI::PositiveNumber);
  command->add_option("--threads", options->overrides.threads,
                         "Threads of each step: a count or hardware (default: the scene's, 1); "
                         "results are bit-identical whatever the count (docs/embedding.md)");
  command->add_option("--dt", options->overrides.timeStep, "Time step [s] (default: the scene's)");
  command->add_option("--max-iter", options->overrides.maxIterations,
                      "Iteration cap per island solve (0 = each solver's default)");
  command->add_option("--tol", options->overrides.tolerance,
                      "Target common relative residual (default: the world's, 1e-6)");
  command
      ->add_option("--time-cap", options->timeCap,
                   "Stop a solver's run when its summed step time exceeds this [s] (default: "
                   "none); the row then says how much was simulated")
      ->check(CLI::PositiveNumber);
  command->callback([options] { compare(*options); });
}

}  // namespace coulomb::cli
