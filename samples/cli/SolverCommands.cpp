// Placeholder until the solvers land (issue 5): `coulomb solvers` and `coulomb solve`.
#include "Commands.hpp"

namespace coulomb::cli {
void registerSolverCommands(CLI::App& /*app*/) {}
}  // namespace coulomb::cli
