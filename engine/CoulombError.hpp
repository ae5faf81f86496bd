#pragma once
// The one exception type the engine throws for bad input (a body description, a scene file, a
// settings value). The message names the offending value and, when known, where it came from.
#include <stdexcept>
#include <string>

namespace coulomb::engine {

struct CoulombError : std::runtime_error {
  explicit CoulombError(const std::string& message) : std::runtime_error(message) {}
};

}  // namespace coulomb::engine
