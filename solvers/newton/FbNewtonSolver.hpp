#pragma once
// fb_newton: the global nonsmooth Newton of runNonsmoothNewton on the Fischer-Burmeister function
// for second-order cones (docs/solver-derivations.md section 6), De Saxce formulation (6.1). It
// shares the loop, the generalized Jacobian J = A W + B, the row elimination (5.7), the
// regularization (5.8) and both line searches with ac_newton; only the per-contact function
// differs. Default line search: Armijo (5.11), well founded because the FB merit is C^1 (Chen,
// Tseng, Math. Prog. 104 2005).
#include <coulomb/solvers/ContactSolver.hpp>
#include <coulomb/solvers/newton/NonsmoothNewton.hpp>

namespace coulomb::solvers {

struct FbNewtonOptions {
  // rho per contact (5.14) (SPECTRAL by default), regularization (5.8), stall test (5.12). The
  // line search defaults to Armijo (5.11) here; Goldstein-Price is available. No watchdog: the
  // Fischer-Burmeister merit is smooth (C^1), so the full steps that raise Alart-Curnier's merit
  // at its kinks (NewtonSettings::watchdogSteps) are not what stops it (docs/solvers.md
  // "Watchdog Newton").
  NewtonSettings newton = armijoSettings();

  static NewtonSettings armijoSettings() {
    NewtonSettings s;
    s.lineSearch = NewtonSettings::LineSearch::Armijo;
    s.watchdogSteps = 0;
    return s;
  }
};

class FbNewtonSolver final : public ContactSolver {
 public:
  explicit FbNewtonSolver(FbNewtonOptions options = {}) : options_(options) {}
  [[nodiscard]] std::string name() const override { return "fb_newton"; }
  [[nodiscard]] const FbNewtonOptions& options() const { return options_; }
  void solvePrepared(const PreparedProblem& problem, const SolveContext& context,
                     Eigen::VectorXd& r, SolverReport& report) const override;
  // One Newton step with the factors of the last iteration (newtonStepWithKeptFactors).
  [[nodiscard]] bool steadyAnswer(const PreparedProblem& problem, const Eigen::VectorXd& r,
                                  const Eigen::VectorXd& uShifted,
                                  Eigen::VectorXd& out) const override;

 private:
  FbNewtonOptions options_;
  // Kept between solves for its storage (ContactSolver::solve: one instance, one thread).
  mutable NewtonWorkspace workspace_{options_.newton};
};

}  // namespace coulomb::solvers
