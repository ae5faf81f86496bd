#include <coulomb/solvers/newton/FbNewtonSolver.hpp>

#include <coulomb/solvers/newton/FischerBurmeisterFunction.hpp>

#include <cstdio>

namespace coulomb::solvers {

void FbNewtonSolver::solvePrepared(const PreparedProblem& p, const SolveContext& context,
                                   Eigen::VectorXd& r, SolverReport& report) const {
  const FischerBurmeisterFunction function;
  runNonsmoothNewton(p, function, options_.newton, context,
                     context.maxIterations(options_.newton.defaultMaxIterations), r, report,
                     &workspace_);
  if (report.maxRegularization > 0 && p.maxDiagonal > 0) {
    char msg[80];  // on the stack: a steady step allocates nothing
    std::snprintf(msg, sizeof msg, "J regularized by (5.8), sigma up to %g max W_ii",
                  report.maxRegularization / p.maxDiagonal);
    report.note(msg);
  }
}

bool FbNewtonSolver::steadyAnswer(const PreparedProblem& p, const Eigen::VectorXd& r,
                                  const Eigen::VectorXd& uShifted, Eigen::VectorXd& out) const {
  const FischerBurmeisterFunction function;
  return newtonStepWithKeptFactors(p, function, workspace_, r, uShifted, out);
}

}  // namespace coulomb::solvers
