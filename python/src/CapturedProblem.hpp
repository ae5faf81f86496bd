#pragma once
// An island's problem captured from a stepping World (coulomb.CapturedProblem), for
// coulomb.capture_problems and World.step_capturing (CaptureBindings.cpp).
#include <coulomb/engine/World.hpp>
#include <coulomb/solvers/ContactProblem.hpp>

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace coulomb::python {

struct CapturedProblem {
  std::uint64_t step = 0;  // index of the step (0 = the first)
  std::int32_t island = 0;
  solvers::ContactProblem problem;  // owns a block-sparse W; named <name>_step<N>_island<K>
};

/// Steps `world` `steps` times and returns each island's problem as its solver received it (of
/// every step, or of step `onlyStep`). No Python object is touched (runs without the GIL).
std::vector<CapturedProblem> stepCapturing(engine::World& world, std::uint64_t steps,
                                           std::optional<std::uint64_t> onlyStep,
                                           const std::string& name);

}  // namespace coulomb::python
