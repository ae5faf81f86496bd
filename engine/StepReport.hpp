#pragma once
// What one World::step did. Later stages (islands, contacts, solver reports, fallbacks) add their
// fields here as they land (ARCHITECTURE.md section 2).
#include <cstddef>
#include <cstdint>

namespace coulomb::engine {

struct StepReport {
  std::uint64_t stepIndex = 0;    // index of this step (0 for the first)
  double timeStep = 0.0;          // [s] h used
  double time = 0.0;              // [s] simulated time at the end of the step
  std::size_t dynamicBodies = 0;  // bodies integrated under forces
  std::size_t kinematicBodies = 0;
};

}  // namespace coulomb::engine
