#pragma once
// A scene with a caller's overrides (time step, step count, solver, tolerance, iteration cap,
// friction, joints' energy target, URDF base): what `coulomb run --dt --steps --solver --tol
// --max-iter --mu --joint-energy` and Python's coulomb.run(dt=, steps=, solver=, tol=,
// max_iterations=, mu=, joint_energy=) change, in one place.
#include <coulomb/io/SceneLoader.hpp>

#include <cstdint>
#include <optional>
#include <string>

namespace coulomb::scenes {

struct SceneOverrides {
  std::optional<std::string> solver;  // "auto", a registry name, "name!" or "a,b,c"
  std::optional<double> timeStep;     // [s]
  std::optional<std::uint64_t> steps;
  std::optional<int> maxIterations;  // solver iteration cap per island (0 = solver default)
  std::optional<double> tolerance;   // common relative residual target
  std::optional<double> friction;    // mu of every shape's material
  // The energy target of every joint under the predicted-state policy: "none", "modified" or
  // "exact" (joints::PredictedStateSettings::energy; docs/tuning.md "Chains keep their energy").
  std::optional<std::string> jointEnergy;
  bool urdfFloating = false;           // a .urdf scene: floating base (default fixed)
  bool urdfLimp = false;               // a .urdf scene: no motors holding the joints
  bool urdfMaximal = false;            // a .urdf scene: free bodies and maximal joints
  std::optional<std::string> threads;  // "hardware" or a count >= 1 (WorldSettings::threads)
};

/// WorldSettings::threads from "hardware" (0: every hardware thread) or a count in
/// 1..WorldSettings::kMaxThreads; throws CoulombError naming `who` otherwise.
int parseThreads(const std::string& text, const std::string& who);

/// Applies the overrides. A solver override replaces the world's solver and clears every body's
/// own `solver`, so that every island uses it. Throws CoulombError naming the override and the
/// problem ("time step override: must be finite and > 0 s").
void applyOverrides(engine::io::Scene& scene, const SceneOverrides& overrides);

/// The scene `nameOrPath` (a built-in name, a JSON file or a .urdf robot on a floor, docs/urdf.md
/// "In a scene") with the overrides applied. Throws CoulombError.
engine::io::Scene resolveScene(const std::string& nameOrPath, const SceneOverrides& overrides);

}  // namespace coulomb::scenes
