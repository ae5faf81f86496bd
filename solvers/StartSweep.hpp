#pragma once
// One blocked Gauss-Seidel sweep over the contacts of a problem whose W has its entries (block-
// sparse: the World's small islands), each contact given its exact local answer
// (docs/solver-derivations.md (4.1)) against the others' current impulses; scalar rows keep their
// values. ContactSolver refines a start that misses the tolerance with it before a solver that
// does not sweep (Newton) iterates (SolverOptions::startSweep, docs/solvers.md "Start sweep"): a
// resting or steadily loaded island whose warm start drifted a little past the tolerance is back
// at rounding after one sweep of 3 x 3 solves, where a Newton iteration forms and factors the
// whole system.
#include <coulomb/solvers/PreparedProblem.hpp>

#include <Eigen/Core>

namespace coulomb::solvers {

// r := r after one sweep, contacts in block order. Requires W's entries (problem.bodySpace
// null); false (r unchanged) without them.
bool sweepContacts(const PreparedProblem& problem, Eigen::VectorXd& r);

}  // namespace coulomb::solvers
