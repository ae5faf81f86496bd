#include <coulomb/solvers/ContactSolver.hpp>

#include <coulomb/solvers/Residual.hpp>

#include <cmath>
#include <exception>

namespace coulomb::solvers {

SolveOutcome ContactSolver::solve(const ContactProblem& problem,
                                  const SolverOptions& options) const {
  return run(problem, options, nullptr);
}

SolveOutcome ContactSolver::solve(const ContactProblem& problem, const SolverOptions& options,
                                  const Eigen::VectorXd& start) const {
  return run(problem, options, &start);
}

SolveOutcome ContactSolver::run(const ContactProblem& problem, const SolverOptions& options,
                                const Eigen::VectorXd* start) const {
  const auto t0 = SolveContext::Clock::now();
  SolveOutcome out;
  SolverReport& report = out.report;
  report.solver = name();
  auto finish = [&]() -> SolveOutcome {
    report.seconds = std::chrono::duration<double>(SolveContext::Clock::now() - t0).count();
    return std::move(out);
  };
  if (auto bad = validateOptions(options)) {
    report.status = SolverStatus::InvalidProblem;
    report.note("invalid options: " + *bad);
    return finish();
  }
  if (auto bad = problem.validate()) {
    report.status = SolverStatus::InvalidProblem;
    report.note(*bad);
    return finish();
  }
  const int n = problem.size();
  out.impulses = Eigen::VectorXd::Zero(n);
  out.velocities = problem.q;
  if (auto why = notApplicable(problem)) {
    report.status = SolverStatus::NotApplicable;
    report.note(*why);
    return finish();
  }
  if (n == 0) {
    report.status = SolverStatus::Converged;
    report.residual = report.absoluteResidual = report.nativeResidual = 0.0;
    report.note("no unknowns");
    return finish();
  }
  const SolveContext context(options, t0);
  PreparedProblem prepared;
  try {
    prepared = PreparedProblem::from(problem, worksInBodySpace());
  } catch (const std::exception& e) {
    report.status = SolverStatus::InvalidProblem;
    report.note(std::string("cannot prepare the problem: ") + e.what());
    return finish();
  }
  // Start: the given one, else the warm start, kept only if it beats r = 0 (SOLVERS.md (3.6)).
  // Each candidate's residual keeps its dv (body space), handed to the solver with the chosen
  // start (PreparedProblem::start) so that it does not compute them again.
  Eigen::VectorXd u, dv, r = Eigen::VectorXd::Zero(n);
  double e = prepared.residual(r, u, dv);
  const Eigen::VectorXd* candidate =
      start ? start : (options.useWarmStart && problem.warmStart ? &*problem.warmStart : nullptr);
  if (candidate) {
    if (candidate->size() != n || !candidate->allFinite()) {
      report.note("start ignored (wrong size or not finite)");
    } else {
      Eigen::VectorXd s = prepared.fromOriginal(*candidate);
      prepared.project(s);
      Eigen::VectorXd dvs;
      const double es = prepared.residual(s, u, dvs);
      if (es <= e) {
        r = s;
        e = es;
        dv.swap(dvs);
      } else {
        report.note("warm start ignored: r = 0 has a smaller residual");
      }
    }
  }
  const Eigen::VectorXd r0 = r;
  if (e <= options.tolerance) {
    report.status = SolverStatus::Converged;
    report.nativeResidual = e;
    report.nativeResidualName = "common residual of the start";
  } else {
    prepared.start.known = true;
    prepared.start.r = r;
    prepared.start.dv.swap(dv);
    prepared.start.residual = e;
    try {
      solvePrepared(prepared, context, r, report);
    } catch (const std::exception& ex) {
      report.status = SolverStatus::NumericalFailure;
      report.note(std::string("exception: ") + ex.what());
      r = r0;
    }
    if (!r.allFinite()) {
      report.status = SolverStatus::NumericalFailure;
      report.note("non-finite iterate replaced by the start");
      r = r0;
    }
  }
  out.impulses = prepared.toOriginal(r);
  const ResidualValue res = commonResidual(problem, out.impulses, out.velocities);
  report.residual = res.relative;
  report.absoluteResidual = res.absolute;
  if (!std::isfinite(report.residual)) {  // cannot happen with finite r and a valid problem
    report.status = SolverStatus::NumericalFailure;
    out.impulses.setZero();
    out.velocities = problem.q;
    report.residual = commonResidual(problem, out.impulses).relative;
  }
  if (report.status == SolverStatus::Converged && report.residual > options.tolerance) {
    report.status = SolverStatus::Stalled;
    report.note("internal test met but the common residual is above the tolerance");
  } else if (report.status != SolverStatus::Converged &&
             report.status != SolverStatus::InvalidProblem &&
             report.residual <= options.tolerance) {
    report.status = SolverStatus::Converged;
  }
  return finish();
}

}  // namespace coulomb::solvers
