#include <coulomb/solvers/newton/FbNewtonSolver.hpp>

#include <coulomb/solvers/newton/FischerBurmeisterFunction.hpp>

#include <sstream>

namespace coulomb::solvers {

void FbNewtonSolver::solvePrepared(const PreparedProblem& p, const SolveContext& context,
                                   Eigen::VectorXd& r, SolverReport& report) const {
  const FischerBurmeisterFunction function;
  runNonsmoothNewton(p, function, options_.newton, context,
                     context.maxIterations(options_.newton.defaultMaxIterations), r, report,
                     &workspace_);
  if (report.maxRegularization > 0 && p.maxDiagonal > 0) {
    std::ostringstream msg;
    msg << "J regularized by (5.8), sigma up to " << report.maxRegularization / p.maxDiagonal
        << " max W_ii";
    report.note(msg.str());
  }
}

}  // namespace coulomb::solvers
