#pragma once
// The invariants every registered solver owes any problem (ContactSolver.hpp, SolverReport.hpp).
#include <coulomb/solvers/ContactProblem.hpp>

#include <string>

namespace coulomb::fuzz {

// validate(), then every solver of SolverRegistry::builtIn() with at most `maxIterations`
// iterations and 0.25 s: a valid status; InvalidProblem exactly when validate() refuses; otherwise
// problem.size() impulses, all finite; Converged only with the common residual <= tolerance.
std::string solveWithEverySolver(const solvers::ContactProblem& problem, int maxIterations);

}  // namespace coulomb::fuzz
