#include <coulomb/solvers/newton/AcNewtonSolver.hpp>

#include <coulomb/solvers/Residual.hpp>
#include <coulomb/solvers/bgs/BgsSolver.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace coulomb::solvers {

namespace {

// Proximal point (5.9) from r (best so far): subproblems FC(W + sigma I, q - sigma r_k).
template <class ProximalWorkspace>
void proximalLoop(const PreparedProblem& p, const AlartCurnierFunction& f, const AcNewtonOptions& o,
                  const SolveContext& context, int budget, Eigen::VectorXd& r, SolverReport& report,
                  NewtonWorkspace& workspace, ProximalWorkspace& scratch) {
  double meanDiag = 0;
  for (int i = 0; i < p.size(); ++i) meanDiag += p.diagonal(i);
  meanDiag /= std::max(1, p.size());
  double sigma = o.proximalInitialShift * meanDiag;
  Eigen::VectorXd &u = scratch.u, &best = scratch.best, &x = scratch.x;
  best = r;
  double eAbsolute = 0.0;
  double e = p.residual(r, u, &eAbsolute), bestE = e;
  PreparedProblem& inner = scratch.inner;
  inner = p;
  // One workspace (and linear solver) for all subproblems: W + sigma I keeps W's structure, so
  // the sparse pattern and its symbolic analysis carry over from one subproblem to the next.
  const double tol = context.tolerance();
  int outer = 0, used = 0;
  while (used < budget && bestE > tol) {
    if (context.timeUp(report)) break;
    ++outer;
    inner.writableW().assignShiftedDiagonal(p.W(), sigma);  // inner.W() is p.W()'s (inner = p)
    inner.factorsShift = p.factorsShift + sigma;
    inner.q = p.q;
    inner.q -= sigma * r;
    inner.qNorm = plainNorm(inner.q);
    // The subproblem's start is r, where its u = (W + sigma I) r + q - sigma r is the problem's:
    // handed over, not computed again (the same absolute residual, relative to the new q).
    PreparedProblem::KnownEvaluation& start = inner.start;
    start.known = !inner.bodySpace;
    start.r = r;
    start.u = u;
    start.absolute = eAbsolute;
    start.residual = eAbsolute / (1.0 + inner.qNorm);
    start.inBodySpace = false;
    SolverOptions innerOptions = context.options();
    innerOptions.tolerance = std::max(tol / 10, std::min(1e-2, e / 10));
    innerOptions.recordHistory = false;
    const SolveContext innerContext = context.withOptions(innerOptions);
    SolverReport& innerReport = scratch.innerReport;
    innerReport.reset();
    x = r;
    runNonsmoothNewton(inner, f, o.newton, innerContext,
                       std::min(o.proximalInnerIterations, budget - used), x, innerReport,
                       &workspace);
    used += std::max(1, innerReport.iterations);
    report.lineSearchFailures += innerReport.lineSearchFailures;
    report.maxRegularization = std::max(report.maxRegularization, innerReport.maxRegularization);
    if (innerReport.timeLimitReached) report.timeLimitReached = true;
    if (!x.allFinite()) break;
    r = x;
    e = p.residual(r, u, &eAbsolute);
    context.record(report, report.iterations + used, e);
    if (e < bestE) bestE = e, best = r;
    // The shift falls by at most proximalShrink per subproblem: that far after an easy one,
    // else toward 5 e mean W_ii (Siconos' PROX); it rises tenfold after one Newton did not solve.
    if (innerReport.status == SolverStatus::Converged) {
      const bool easy = innerReport.iterations <= o.proximalQuickInner;
      sigma = std::max(o.proximalShrink * sigma, easy ? 0.0 : std::min(sigma, 5.0 * e * meanDiag));
    } else {
      sigma *= 10.0;
    }
    sigma = std::max(sigma, 1e-14 * meanDiag);
  }
  inner.factors.reset();  // the problem's factors and W: the caller's to release
  inner.sharedW.reset();
  report.iterations += used;
  r = best;
  // Formatted on the stack: a steady step allocates nothing (docs/architecture.md, memory).
  char msg[96];
  std::snprintf(msg, sizeof msg, "proximal point (5.9): %d subproblems, %d Newton iterations",
                outer, used);
  report.note(msg);
  report.status = bestE <= tol              ? SolverStatus::Converged
                  : report.timeLimitReached ? SolverStatus::MaxIterations
                  : used >= budget          ? SolverStatus::MaxIterations
                                            : SolverStatus::Stalled;
}

}  // namespace

void AcNewtonSolver::solvePrepared(const PreparedProblem& p, const SolveContext& context,
                                   Eigen::VectorXd& r, SolverReport& report) const {
  const int budget = context.maxIterations(options_.newton.defaultMaxIterations);
  workspace_.factoredFor = nullptr;  // a solve that runs no Newton step leaves no factors
  if (options_.hybridSweeps > 0) {   // hybrid start (a): a few bgs sweeps
    SolverOptions gsOptions = context.options();
    gsOptions.maxIterations = options_.hybridSweeps;
    gsOptions.recordHistory = false;
    SolverReport gsReport;
    sweeps_.solvePrepared(p, context.withOptions(gsOptions), r, gsReport);
    report.note("hybrid start: " + std::to_string(gsReport.iterations) + " bgs sweeps");
    if (gsReport.status == SolverStatus::Converged) {
      report.status = SolverStatus::Converged;
      report.iterations = 0;
      return;
    }
  }
  const AlartCurnierFunction function(options_.radius);
  if (options_.proximalFromStart) {
    proximalLoop(p, function, options_, context, budget, r, report, workspace_, proximal_);
    return;
  }
  // Plain Newton first; with the proximal loop to hand over to, a return to the watchdog point
  // (full steps that led nowhere: a degenerate answer) ends it at once (watchdogReturnStalls).
  NewtonSettings plain = options_.newton;
  plain.watchdogReturnStalls = options_.proximalOnStall && options_.handOverOnWatchdogReturn;
  runNonsmoothNewton(p, function, plain, context, budget, r, report, &workspace_);
  // Stall restart (hybrid (b) inside the solver, docs/solver-derivations.md section 5; Siconos'
  // NSN_AND_PLI_NSN_LOOP): a stalled Newton sits in a local minimum of psi = 1/2 ||Phi||^2 that
  // is no solution, typically on the kink ||y_T|| = delta of one contact, where the Newton
  // directions of both sides cross the kink and raise psi (docs/solvers.md, "ac_newton stall
  // restart"). No descent method on psi leaves it; bgs sweeps do not look at psi, so a few of them
  // from r_best give a new start, from which Newton continues.
  int restarts = 0, accepted = 0, restartSweeps = 0;
  while (restarts < options_.stallRestarts && report.status == SolverStatus::Stalled &&
         report.iterations < budget && !report.timeLimitReached) {
    ++restarts;
    Eigen::VectorXd &u = proximal_.u, &before = proximal_.before;
    before = r;
    const double beforeE = p.residual(r, u);
    SolverOptions gsOptions = context.options();
    gsOptions.maxIterations = std::min(options_.restartSweeps, budget - report.iterations);
    gsOptions.recordHistory = false;
    SolverReport& gsReport = proximal_.sweepReport;
    gsReport.reset();
    sweeps_.solvePrepared(p, context.withOptions(gsOptions), r, gsReport);
    report.iterations += gsReport.iterations;
    restartSweeps += gsReport.iterations;
    if (gsReport.status == SolverStatus::Converged) {
      report.status = SolverStatus::Converged;
      break;
    }
    // Continue Newton only where bgs clearly makes progress (e_rel down by restartGain): where
    // it does not (bgs plateaus near the tolerance on Capsules-i122, slow bgs on RockPile) the
    // proximal loop (5.9) takes over from Newton's best with the budget left, as before.
    if (!(p.residual(r, u) < options_.restartGain * beforeE)) {
      r = before;
      report.status = SolverStatus::Stalled;
      break;
    }
    ++accepted;
    if (report.iterations >= budget) {
      report.status = SolverStatus::MaxIterations;
      break;
    }
    runNonsmoothNewton(p, function, options_.newton, context, budget - report.iterations, r, report,
                       &workspace_);
  }
  if (restarts > 0) {
    char msg[128];
    std::snprintf(msg, sizeof msg,
                  "stall restart: %d x bgs (%d sweeps), %d improved on Newton's best and "
                  "restarted it",
                  restarts, restartSweeps, accepted);
    report.note(msg);
  }
  // The regularization (5.8) is reported as a number (SolverReport::maxRegularization), not
  // formatted into the message: this runs on most solves of a step.
  if (options_.proximalOnStall && report.status == SolverStatus::Stalled &&
      report.iterations < budget && !report.timeLimitReached)
    proximalLoop(p, function, options_, context, budget - report.iterations, r, report, workspace_,
                 proximal_);
}

bool AcNewtonSolver::steadyAnswer(const PreparedProblem& p, const Eigen::VectorXd& r,
                                  const Eigen::VectorXd& uShifted, Eigen::VectorXd& out) const {
  const AlartCurnierFunction function(options_.radius);
  return newtonStepWithKeptFactors(p, function, workspace_, r, uShifted, out);
}

}  // namespace coulomb::solvers
