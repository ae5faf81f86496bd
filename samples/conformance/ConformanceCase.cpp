#include "ConformanceCase.hpp"

#include "scenes/SceneRegistry.hpp"

#include <coulomb/engine/CoulombError.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>

namespace coulomb::conformance {

const engine::StepReport& RunRecorder::step(engine::World& world) {
  const auto start = std::chrono::steady_clock::now();
  last_ = world.step();
  seconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  ++steps_;
  for (const engine::IslandReport& island : last_.islands) {
    maxResidual_ = std::max(maxResidual_, island.solve.residual);
    iterationSum_ += island.solve.iterations;
    maxIterations_ = std::max(maxIterations_, island.solve.iterations);
    ++solves_;
  }
  fallbacks_ += last_.fallbacks();
  stateHash_ = world.stateHash();  // outside the timed part
  return last_;
}

void RunRecorder::finish(CaseRun& run) const {
  run.steps = steps_;
  run.msPerStep = steps_ == 0 ? 0.0 : 1e3 * seconds_ / static_cast<double>(steps_);
  run.maxResidual = maxResidual_;
  run.meanIterations = solves_ == 0 ? 0.0 : iterationSum_ / static_cast<double>(solves_);
  run.maxIterations = maxIterations_;
  run.fallbacks = fallbacks_;
  run.stateHash = stateHash_;
}

engine::World buildCaseWorld(const std::string& scene, const CaseOptions& options) {
  engine::io::Scene loaded = scenes::loadBuiltinScene(scene);
  loaded.settings.solve.choice = coulomb::solvers::solverChoice(options.solver);
  return engine::io::buildWorld(loaded);
}

std::size_t scaledSteps(std::size_t steps, const CaseOptions& options) {
  const double scaled = std::ceil(static_cast<double>(steps) * options.horizonScale);
  return std::max<std::size_t>(1, static_cast<std::size_t>(scaled));
}

const std::vector<ConformanceCase>& allCases() {
  static const std::vector<ConformanceCase> cases = [] {
    std::vector<ConformanceCase> all;
    // One line per case group (each helper file adds its own).
    addFrictionCases(all);
    addImpactCases(all);
    addLoopCases(all);
    addStabilityCases(all);
    addStructureCases(all);
    return all;
  }();
  return cases;
}

const ConformanceCase& findCase(const std::string& name) {
  const std::vector<ConformanceCase>& cases = allCases();
  const auto found = std::find_if(cases.begin(), cases.end(),
                                  [&](const ConformanceCase& c) { return c.name == name; });
  if (found != cases.end()) return *found;
  std::string names;
  for (const ConformanceCase& c : cases) names += (names.empty() ? "" : ", ") + c.name;
  throw engine::CoulombError("no conformance case '" + name + "' (known: " + names + ")");
}

const std::vector<std::string>& tableSolvers() {
  // Each named solver alone (NAME!: no fallback), so the table shows what that solver does; auto
  // is the default plan with its fallbacks.
  static const std::vector<std::string> solvers = {
      "auto", "pgs!", "bgs!", "ac_newton!", "fb_newton!", "staggered!", "lemke!"};
  return solvers;
}

}  // namespace coulomb::conformance
