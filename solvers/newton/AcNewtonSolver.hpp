#pragma once
// ac_newton: the global Alart-Curnier nonsmooth Newton of AC11 (Bertails-Descoubes et al., ACM TOG
// 30(1) 2011, section 4, Algorithms 1-2) on the reduced form, docs/solver-derivations.md section 5,
// with the residual-scaled regularization (5.8) for redundant contacts and, when plain Newton
// stalls, the proximal-point outer loop (5.9) around the same Newton.
#include <coulomb/solvers/ContactSolver.hpp>
#include <coulomb/solvers/bgs/BgsSolver.hpp>
#include <coulomb/solvers/newton/NewtonFunction.hpp>
#include <coulomb/solvers/newton/NonsmoothNewton.hpp>

namespace coulomb::solvers {

struct AcNewtonOptions {
  // rho per contact (5.14), regularization (5.8), line search (5.10), stall test (5.12), dense
  // threshold: see NewtonSettings. Defaults: SPECTRAL rho, sigma in [1e-12, 1e-4] max W_ii,
  // Goldstein-Price m1 = 0.1, m2 = 0.9, 30 trials, watchdog of 10 steps, Stalled after 20
  // iterations without 1 %.
  NewtonSettings newton;
  // Radius of the friction disk: (5.2a) mu [y_N]_+ (default: AC91 and Siconos' default) or
  // (5.2b) mu r_N.
  AlartCurnierFunction::Radius radius = AlartCurnierFunction::Radius::PositivePart;
  // [sweeps] of bgs before Newton (hybrid start (a) of docs/solver-derivations.md section 5).
  // Default 0: on the corpus it did not rescue the hard cases, whose obstacle is the singular J.
  int hybridSweeps = 0;
  // When Newton stalls, continue with the proximal point method (5.9) from the best iterate:
  // r_{k+1} solves FC(W + s_k I, q - s_k r_k) by the same Newton. Default on: it solved the
  // Kaplas tower in the prototypes where plain Newton (with (5.8)) did not.
  bool proximalOnStall = true;
  // With proximalOnStall: plain Newton ends at its first return to the watchdog point (full
  // steps that led nowhere, NewtonSettings::watchdogReturnStalls) and the stall handling below
  // takes over. Measured on box_pile_1000's landing: ~10 plain iterations where the stall tests
  // needed ~20 (docs/solvers.md "Watchdog Newton").
  bool handOverOnWatchdogReturn = true;
  // When Newton stalls, restart it at most this many times from the point reached by
  // `restartSweeps` bgs sweeps from its best iterate (before the proximal point): a stall is a
  // local minimum of psi = 1/2 ||Phi||^2 that no descent on psi leaves (docs/solvers.md,
  // "ac_newton stall restart"; Siconos' NSN_AND_PLI_NSN_LOOP hybrid). The sweeps count as
  // iterations. 0 disables.
  int stallRestarts = 3;
  int restartSweeps = 5;
  // [-] the restart is taken only if the sweeps cut e_rel below restartGain x Newton's best
  // (measured after 5 sweeps: 0.10 on the double-loop capture, 0.40 on Capsules-i122, 0.67 on
  // RockPile, where the proximal loop does better with the budget).
  double restartGain = 0.25;
  // Run the proximal-point loop (5.9) from the start instead of after a stall: the `prox` entry of
  // the registry (Siconos' PROX). Default off: on well-posed problems plain Newton is faster.
  bool proximalFromStart = false;
  // [-] first proximal shift as a multiple of mean_i W_ii (docs/solver-derivations.md (5.9),
  // scale-aware version of Siconos' absolute 1e4).
  double proximalInitialShift = 1.0;
  // [Newton iterations] cap per proximal subproblem.
  int proximalInnerIterations = 50;
  // The proximal shift falls by at most proximalShrink per solved subproblem: by that factor
  // after one Newton solved within proximalQuickInner iterations, else toward 5 e mean W_ii
  // (Siconos' PROX); it rises tenfold after one Newton did not solve. The loop gains about
  // sigma / (sigma + lambda) per subproblem along an eigenvalue lambda of W, so a shift Newton
  // handles easily is larger than it needs to be (box piles: 40-60 subproblems of 1-2 Newton
  // iterations at ~6 % each under the residual rule alone), and a shift dropped at once to 5 e
  // fails and climbs back decade by decade, again and again (RockPile_tob1: 60 % of the
  // iterations in failed subproblems). docs/solvers.md "The proximal shift and the slow stall".
  int proximalQuickInner = 3;
  double proximalShrink = 0.3;
};

class AcNewtonSolver final : public ContactSolver {
 public:
  explicit AcNewtonSolver(AcNewtonOptions options = {}) : options_(options) {}
  [[nodiscard]] std::string name() const override {
    return options_.proximalFromStart ? "prox" : "ac_newton";
  }
  [[nodiscard]] const AcNewtonOptions& options() const { return options_; }
  void solvePrepared(const PreparedProblem& problem, const SolveContext& context,
                     Eigen::VectorXd& r, SolverReport& report) const override;
  // One Newton step with the factors of the last iteration (newtonStepWithKeptFactors).
  [[nodiscard]] bool steadyAnswer(const PreparedProblem& problem, const Eigen::VectorXd& r,
                                  const Eigen::VectorXd& uShifted,
                                  Eigen::VectorXd& out) const override;

 private:
  AcNewtonOptions options_;
  // Kept between solves for their storage (ContactSolver::solve: one instance, one thread).
  mutable NewtonWorkspace workspace_{options_.newton};
  mutable BgsSolver sweeps_;  // the hybrid start's and the stall restart's bgs sweeps
  // The proximal loop's subproblem and the restart's and the loop's vectors.
  struct ProximalWorkspace {
    PreparedProblem inner;
    Eigen::VectorXd u, best, x, before;
    SolverReport innerReport, sweepReport;
  };
  mutable ProximalWorkspace proximal_;
};

}  // namespace coulomb::solvers
