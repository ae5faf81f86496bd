#include "SceneOverrides.hpp"

#include <coulomb/engine/CoulombError.hpp>
#include <coulomb/io/UrdfScene.hpp>

#include <algorithm>
#include <cmath>

#include "SceneRegistry.hpp"

namespace coulomb::scenes {

using engine::CoulombError;

int parseThreads(const std::string& text, const std::string& who) {
  if (text == "hardware") return 0;
  const bool digits =
      !text.empty() && text.size() <= 6 &&
      std::all_of(text.begin(), text.end(), [](char c) { return c >= '0' && c <= '9'; });
  const int count = digits ? std::stoi(text) : -1;
  if (count < 1 || count > engine::WorldSettings::kMaxThreads)
    throw CoulombError(who + ": must be a thread count in 1.." +
                       std::to_string(engine::WorldSettings::kMaxThreads) +
                       " or \"hardware\" (got \"" + text + "\")");
  return count;
}

void applyOverrides(engine::io::Scene& scene, const SceneOverrides& overrides) {
  if (overrides.threads)
    scene.settings.threads = parseThreads(*overrides.threads, "threads override");
  if (overrides.timeStep) {
    if (!std::isfinite(*overrides.timeStep) || *overrides.timeStep <= 0.0)
      throw CoulombError("time step override: must be finite and > 0 s");
    scene.settings.timeStep = *overrides.timeStep;
  }
  if (overrides.steps) scene.steps = *overrides.steps;
  if (overrides.solver) {
    std::string error;
    const std::optional<solvers::SolverChoice> choice =
        solvers::parseSolverChoice(*overrides.solver, error);
    if (!choice) throw CoulombError("solver override: " + error);
    scene.settings.solve.choice = *choice;
    for (engine::BodyDesc& body : scene.bodies) body.solver.reset();
  }
  if (overrides.maxIterations) {
    if (*overrides.maxIterations < 0) throw CoulombError("iteration cap override: must be >= 0");
    scene.settings.solve.options.maxIterations = *overrides.maxIterations;
  }
  if (overrides.tolerance) {
    if (!std::isfinite(*overrides.tolerance) || *overrides.tolerance <= 0.0)
      throw CoulombError("tolerance override: must be finite and > 0");
    scene.settings.solve.options.tolerance = *overrides.tolerance;
  }
  if (overrides.friction) {
    if (!std::isfinite(*overrides.friction) || *overrides.friction < 0.0)
      throw CoulombError("friction override: must be finite and >= 0");
    for (engine::BodyDesc& body : scene.bodies)
      for (engine::ShapeDesc& shape : body.shapes) shape.material.friction = *overrides.friction;
    for (engine::ArticulationDesc& articulation : scene.articulations)
      for (auto& link : articulation.links)
        for (engine::ShapeDesc& shape : link.shapes) shape.material.friction = *overrides.friction;
  }
  if (overrides.jointEnergy) {
    const std::optional<joints::EnergyTarget> energy =
        joints::energyTargetFromName(*overrides.jointEnergy);
    if (!energy)
      throw CoulombError("joint energy override: must be none, modified or exact (got \"" +
                         *overrides.jointEnergy + "\")");
    scene.settings.jointStabilization.predictedState.energy = *energy;
    for (engine::io::SceneJoint& joint : scene.joints)  // a joint's own policy too
      if (joint.def.stabilization) joint.def.stabilization->predictedState.energy = *energy;
  }
}

engine::io::Scene resolveScene(const std::string& nameOrPath, const SceneOverrides& overrides) {
  engine::io::Scene scene =
      nameOrPath.ends_with(".urdf")
          ? engine::io::urdfFileScene(nameOrPath,
                                      overrides.urdfFloating ? engine::io::UrdfBase::Floating
                                                             : engine::io::UrdfBase::Fixed,
                                      !overrides.urdfLimp, {}, overrides.urdfMaximal)
          : resolveScene(nameOrPath);
  applyOverrides(scene, overrides);
  return scene;
}

}  // namespace coulomb::scenes
