#include "entries/FuzzEntries.hpp"

#include <coulomb/engine/CoulombError.hpp>
#include <coulomb/engine/World.hpp>
#include <coulomb/io/SceneLoader.hpp>

#include <exception>
#include <string_view>

namespace coulomb::fuzz {
namespace {

// Small enough that a few steps cost milliseconds (the fuzzer runs thousands of inputs a second).
constexpr std::size_t kMaxStepBodies = 16;
constexpr std::size_t kMaxStepArticulations = 2;
constexpr int kSteps = 3;
constexpr int kMaxIterations = 100;

std::string checkState(const engine::World& world) {
  const geometry::BodyState& s = world.state();
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (!s.alive[i]) continue;
    if (!s.poses[i].position.allFinite() || !s.poses[i].rotation.coeffs().allFinite() ||
        !s.linearVelocities[i].allFinite() || !s.angularVelocities[i].allFinite())
      return "non-finite state of body " + std::to_string(i) + " after step " +
             std::to_string(world.stepCount());
  }
  return {};
}

}  // namespace

std::string sceneEntry(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    // A folder that does not exist: relative mesh and URDF paths of the input resolve to nothing.
    engine::io::Scene scene = engine::io::parseScene(text, "fuzz.json", "/nonexistent-fuzz");
    // Bounded solves: an input asking for 10^9 iterations is valid, not a finding.
    solvers::SolverOptions& options = scene.settings.solve.options;
    if (options.maxIterations <= 0 || options.maxIterations > kMaxIterations)
      options.maxIterations = kMaxIterations;
    engine::World world = engine::io::buildWorld(scene);
    if (scene.bodies.size() > kMaxStepBodies || scene.articulations.size() > kMaxStepArticulations)
      return {};
    for (int k = 0; k < kSteps; ++k) {
      world.step();
      if (std::string bad = checkState(world); !bad.empty()) return bad;
    }
  } catch (const engine::CoulombError&) {
    // refused with a message: the documented outcome of bad input
  } catch (const std::exception& e) {
    return std::string("exception other than CoulombError: ") + e.what();
  }
  return {};
}

}  // namespace coulomb::fuzz
