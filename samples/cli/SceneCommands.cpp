// Placeholder until the foundation lands (issue 3): `coulomb run` and `coulomb scenes`.
#include "Commands.hpp"

namespace coulomb::cli {
void registerSceneCommands(CLI::App& /*app*/) {}
}  // namespace coulomb::cli
