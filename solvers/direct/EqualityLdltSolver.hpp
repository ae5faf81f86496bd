#pragma once
// Problems made of equality rows only (a joint island without limits, motors or contacts): the
// linear system W r = -q solved directly by a sparse LDL^T factorization (Eigen's
// SimplicialLDLT, approximate minimum degree ordering). For a joint island whose bodies and joints
// form a tree (a chain, a rope, a branching mechanism), W = J M^-1 J^T couples only joints that
// share a body, and the elimination ordering follows the tree with no fill-in beyond the body
// cliques: linear time in the number of joints, the direct solve of Baraff 1996 ("Linear-time
// dynamics using Lagrange multipliers", section 7) in Delassus form. A loop (redundant rows, W
// singular) may factor with a tiny pivot: the common residual then decides, and the plan's
// fallback (ac_newton) takes over.
#include <coulomb/solvers/ContactSolver.hpp>

namespace coulomb::solvers {

class EqualityLdltSolver final : public ContactSolver {
 public:
  [[nodiscard]] std::string name() const override { return "ldlt"; }
  [[nodiscard]] std::optional<std::string> notApplicable(
      const ContactProblem& problem) const override;
  void solvePrepared(const PreparedProblem& problem, const SolveContext& context,
                     Eigen::VectorXd& r, SolverReport& report) const override;
};

}  // namespace coulomb::solvers
