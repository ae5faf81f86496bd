#include <coulomb/solvers/ContactSolver.hpp>

#include <coulomb/solvers/Residual.hpp>
#include <coulomb/solvers/StartSweep.hpp>

#include <cmath>
#include <exception>
#include <limits>
#include <sstream>
#include <string_view>

namespace coulomb::solvers {
namespace {

// The relative residual of an exact answer in double precision (the refined sticking start of a
// resting tower: 1e-15 to 1e-13).
constexpr double kRoundOff = std::numeric_limits<double>::epsilon();

}  // namespace

SolveOutcome ContactSolver::solve(const ContactProblem& problem,
                                  const SolverOptions& options) const {
  SolveOutcome out;
  solve(problem, options, nullptr, out);
  return out;
}

SolveOutcome ContactSolver::solve(const ContactProblem& problem, const SolverOptions& options,
                                  const Eigen::VectorXd& start) const {
  SolveOutcome out;
  solve(problem, options, &start, out);
  return out;
}

void ContactSolver::solve(const ContactProblem& problem, const SolverOptions& options,
                          const Eigen::VectorXd* start, SolveOutcome& out) const {
  if (busy_) {  // nested on this instance (a composite solver): a workspace of its own
    Workspace nested;
    run(problem, options, start, out, nested);
    return;
  }
  busy_ = true;
  try {
    run(problem, options, start, out, workspace_);
  } catch (...) {
    busy_ = false;
    throw;
  }
  busy_ = false;
}

void ContactSolver::run(const ContactProblem& problem, const SolverOptions& options,
                        const Eigen::VectorXd* start, SolveOutcome& out, Workspace& work) const {
  const auto t0 = SolveContext::Clock::now();
  SolverReport& report = out.report;
  report.reset();
  out.hasNextWarmStart = false;
  report.solver = name();
  auto finish = [&]() {
    work.prepared.bodySpace.reset();  // the problem's factors: theirs to reuse once it is done
    work.prepared.factors.reset();
    work.prepared.sharedW.reset();  // as the factors: the assembler refills it next step
    work.prepared.diagonalBlocks = nullptr;
    report.seconds = std::chrono::duration<double>(SolveContext::Clock::now() - t0).count();
  };
  if (auto bad = validateOptions(options)) {
    report.status = SolverStatus::InvalidProblem;
    report.note("invalid options: " + *bad);
    out.impulses.setZero(problem.size());
    out.velocities = problem.q;
    return finish();
  }
  const int n = problem.size();
  out.impulses.setZero(n);
  out.velocities = problem.q;
  out.nextWarmStart.resize(n);  // its storage, sized with the others (a steady step allocates
                                // nothing when the next warm start is first kept)
  if (auto bad = problem.validate()) {
    report.status = SolverStatus::InvalidProblem;
    report.note(*bad);
    return finish();
  }
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
  PreparedProblem& prepared = work.prepared;
  try {
    prepared.assign(problem, /*keepBodySpace=*/true);
  } catch (const std::exception& e) {
    report.status = SolverStatus::InvalidProblem;
    report.note(std::string("cannot prepare the problem: ") + e.what());
    return finish();
  }
  // Start: the given one, else the warm start, kept when it is within the tolerance or beats r = 0
  // (docs/solver-derivations.md (3.6)). Each candidate's residual keeps its dv (body space), handed
  // to the solver with the chosen start (PreparedProblem::start) so that it does not compute them
  // again; u is always W r + q for the current r until a solver runs.
  Eigen::VectorXd &u = work.u, &dv = work.dv, &r = work.r;
  r.setZero(n);
  work.stepQ.resize(n);  // sized with the others: its first use in a steady step allocates nothing
  work.arrived.resize(n);
  double eAbsolute = 0.0;  // e's absolute value (PreparedProblem::recordEnd)
  double e = 0.0;
  // r = 0's residual: the bar a start must meet.
  auto evaluateZero = [&] { e = prepared.residual(r, u, dv, &eAbsolute); };
  // work.s (prepared variables) becomes r when `keep` accepts its residual.
  auto keepIf = [&](auto&& keep) {
    Eigen::VectorXd &s = work.s, &dvs = work.dvs, &us = work.us;
    double esAbsolute = 0.0;
    const double es = prepared.residual(s, us, dvs, &esAbsolute);
    if (!keep(es)) return false;
    r.swap(s);
    e = es;
    eAbsolute = esAbsolute;
    dv.swap(dvs);
    u.swap(us);
    return true;
  };
  // ... when its residual is below `e` (or at it).
  auto keepIfBetter = [&](bool tieKeeps) {
    return keepIf([&](double es) { return es < e || (tieKeeps && es == e); });
  };
  // Projected onto the constraint set, kept when its residual is at most `e` (or below it).
  auto tryStart = [&](const Eigen::VectorXd& candidate, bool tieKeeps) {
    prepared.fromOriginal(candidate, work.s);
    prepared.project(work.s);
    return keepIfBetter(tieKeeps);
  };
  const Eigen::VectorXd* warm =
      options.useWarmStart && problem.warmStart ? &*problem.warmStart : nullptr;
  // A direct solver (ignoresStart) computes its answer from no start: trying one would cost a
  // residual (a product with W) for nothing.
  const Eigen::VectorXd* candidate = ignoresStart() ? nullptr : start ? start : warm;
  // A start within the tolerance is an answer whatever r = 0 gives, so r = 0 is evaluated only
  // when the start misses it (a steady stack's warm start: one residual instead of two).
  if (candidate && candidate->size() == n && candidate->allFinite()) {
    prepared.fromOriginal(*candidate, work.s);
    prepared.project(work.s);
    const bool kept = keepIf([&](double es) {
      if (es <= options.tolerance) return true;
      evaluateZero();
      return es <= e;
    });
    if (!kept) report.note("warm start ignored: r = 0 has a smaller residual");
  } else {
    if (candidate) report.note("start ignored (wrong size or not finite)");
    evaluateZero();
  }
  // The all-sticking start (StickingStart.hpp). Without a warm start (a fresh island: no row
  // carried an impulse over) it is tried before the solver; with one (rows new this step start at
  // 0 within it) it is a restart, tried only if a body-space solver has not converged after
  // kStickingRestartSweeps sweeps (ContactSolver.hpp).
  const BodySpaceDelassus* factors = problem.W.bodySpaceOperator();
  const bool sticking = !start && options.stickingStart && factors != nullptr && !ignoresStart();
  StickingStart& stick = options.stickingWorkspace ? *options.stickingWorkspace : work.sticking;
  // One note for both uses, short enough to need no heap: after sweeps (iterations > 0 with a
  // warm start) it was a restart.
  constexpr std::string_view kStickingNote = "sticking start";
  constexpr std::string_view kStartSweepNote = "start sweep";
  // Up front also for a warm-started solver that does not sweep in body space (Newton): one of its
  // iterations assembles W and factors all 3 x contacts unknowns, the start only 6 x bodies ones,
  // so the start is the cheaper first try (a restart after a Newton iteration would come too late).
  const bool upFront = !warm || !worksInBodySpace();
  // A warm-started problem's sticking start is also computed for stepQ = q - J v_k: when it is
  // the answer, that one is the next step's warm start (SolveOutcome::nextWarmStart). Only where
  // the rows' velocities at the step's start, J v_k, are what a solve within the tolerance leaves
  // behind (at most the tolerance of the common residual): larger ones are motion the bodies
  // arrived with (an impact, a throw), whose impulse is part of the answer's physics. Formed
  // when a start is computed (O(rows)): from the bodies' velocities with a body-space W, else by
  // the caller (SolverOptions::arrivalRows). The same rule gives a converged solver's steady
  // answer (steadyAnswer).
  bool stepQKnown = false;
  const Eigen::VectorXd* stepQ = nullptr;
  const Eigen::VectorXd* arrived = nullptr;  // J v_k, when stepQ is known
  Eigen::VectorXd& arrivedQ = work.stepQ;
  auto stepQForStart = [&]() -> const Eigen::VectorXd* {
    if (stepQKnown) return stepQ;
    stepQKnown = true;
    if (!warm) return stepQ;
    if (factors != nullptr && problem.arrival.size() == 6 * factors->bodyCount()) {
      work.arrived.setZero(n);
      factors->addRowVelocities(problem.arrival, work.arrived.data());
      arrived = &work.arrived;
    } else if (factors == nullptr && options.arrivalRows != nullptr) {
      options.arrivalRows->form(work.arrived);
      if (work.arrived.size() != n) return stepQ;
      arrived = &work.arrived;
    } else {
      return stepQ;
    }
    if (plainNorm(*arrived) > options.tolerance * (1.0 + prepared.qNorm)) return stepQ;
    arrivedQ = problem.q - *arrived;
    return stepQ = &arrivedQ;
  };
  // A warm start within the tolerance is an answer, but repeated step after step its error
  // grows: it holds no body against the motion since it was computed, so a stack's tilt grows
  // geometrically (x1.3 per step on a ten-box column of turned boxes), and at the tolerance the
  // column is no longer stickable (its least-norm stop leaves the cones) and Newton takes 100+
  // iterations. A warm start whose residual is past half-way, in orders of magnitude, from
  // round-off to the tolerance is started afresh: geometric growth from a refined start gets
  // there in half its steps to the tolerance, while the column is still stickable; steady drift
  // (a straight tower adds round-off, 1e-15 per step) in 1e4 steps. A rule on the problem alone,
  // no memory of earlier solves, so that a run continued from a snapshot stays bit-identical
  // (docs/solvers.md "Sticking start").
  const bool drifted = warm && e > std::sqrt(kRoundOff * options.tolerance);
  bool answerIsStickingStart = false;  // r is stick.start(), projected
  if (sticking && upFront && (e > options.tolerance || drifted) &&
      stick.compute(*factors, problem.q, problem.blocks, warm, stepQForStart()) &&
      tryStart(stick.start(), false)) {
    report.note(kStickingNote);
    answerIsStickingStart = true;
  }
  const bool restart =
      sticking && warm && worksInBodySpace() && options.maxIterations > kStickingRestartSweeps;
  Eigen::VectorXd& r0 = work.r0;
  r0 = r;
  // The algorithm from r (whose residual is e and body velocities dv), within `runOptions`.
  bool solverRan = false;
  auto runFrom = [&](const SolverOptions& runOptions) {
    solverRan = true;
    prepared.start.known = true;
    prepared.start.r = r;
    prepared.start.dv = dv;
    prepared.start.u = u;
    prepared.start.residual = e;
    prepared.start.absolute = eAbsolute;
    prepared.start.inBodySpace = prepared.bodySpace != nullptr;
    const Eigen::VectorXd& from = prepared.start.r;
    try {
      if (!worksInBodySpace()) prepared.formExplicitW(problem);
      solvePrepared(prepared, context.withOptions(runOptions), r, report);
    } catch (const std::exception& ex) {
      report.status = SolverStatus::NumericalFailure;
      report.note(std::string("exception: ") + ex.what());
      r = from;
    }
    if (!r.allFinite()) {
      report.status = SolverStatus::NumericalFailure;
      report.note("non-finite iterate replaced by the start");
      r = from;
    }
  };
  // The start sweep (StartSweep.hpp): a given or warm start above the tolerance, refined by one
  // exact-local Gauss-Seidel sweep for a solver that does not sweep itself; kept when it lowers
  // the residual (then, within the tolerance, it is the answer).
  if (options.startSweep && candidate != nullptr && e > options.tolerance && !worksInBodySpace() &&
      !prepared.bodySpace) {
    work.s = r;
    if (sweepContacts(prepared, work.s) && keepIfBetter(false)) {
      answerIsStickingStart = false;
      report.note(kStartSweepNote);
    }
  }
  if (e <= options.tolerance) {
    report.status = SolverStatus::Converged;
    report.nativeResidual = e;
    report.nativeResidualName = "common residual of the start";
    prepared.recordEnd(r, u, e, eAbsolute);
  } else if (!restart) {
    answerIsStickingStart = false;
    runFrom(options);
  } else {
    answerIsStickingStart = false;
    SolverOptions firstOptions = options;
    firstOptions.maxIterations = kStickingRestartSweeps;
    runFrom(firstOptions);
    const bool unfinished =
        report.status == SolverStatus::MaxIterations && !report.timeLimitReached;
    if (unfinished) {
      const int used = report.iterations;
      e = prepared.residual(r, u, dv, &eAbsolute);
      // The iterate takes the warm start's place in choosing the stopped contacts: those it
      // loads. It is in the problem's variables: body space is kept only for problems that
      // PreparedProblem does not rescale (no anisotropic cone).
      if (stick.compute(*factors, problem.q, problem.blocks, &r, stepQForStart()) &&
          tryStart(stick.start(), false)) {
        report.note(kStickingNote);
        SolverOptions restOptions = options;
        restOptions.maxIterations = options.maxIterations - used;
        if (e <= options.tolerance) {
          report.status = SolverStatus::Converged;
          report.nativeResidual = e;
          answerIsStickingStart = true;
          prepared.recordEnd(r, u, e, eAbsolute);
        } else {
          runFrom(restOptions);
          report.iterations += used;
        }
      } else {
        // Rejected: the solve runs as it would have without the restart, from its own start (its
        // first sweeps repeated). Continuing from the iterate instead would cut the sweeps'
        // momentum, which is a different iteration: on a collapsing card house it took the
        // collapse along costlier paths (docs/benchmarks.md "Sticking restart").
        r = prepared.start.r;
        dv = prepared.start.dv;
        u = prepared.start.u;
        e = prepared.start.residual;
        eAbsolute = prepared.start.absolute;
        runFrom(options);
        report.iterations += used;
      }
    }
  }
  // The steady answer of a converged solve, kept as the next warm start: the answer holds the
  // load and also removes the velocity error the bodies arrived with (within the tolerance), a
  // one-off that a warm start repeated at the next step would put back with the opposite sign,
  // so that accepted warm starts and Newton iterations alternated on resting islands
  // (docs/solvers.md "Steady warm start").
  // Not after a start sweep: one more sweep on q - J v_k is not exact, and a warm start that
  // leaves an error near the tolerance lets the bodies creep by it, step after step, where an
  // answer that removes the arrival errors stops them every few steps (docs/solvers.md).
  const bool steadyWanted = solverRan && report.status == SolverStatus::Converged &&
                            !answerIsStickingStart && prepared.scale.size() == 0 &&
                            prepared.end.isOf(r);
  if (steadyWanted && stepQForStart() != nullptr) {
    Eigen::VectorXd &uShifted = work.us, &steady = work.s;
    uShifted = prepared.end.u - *arrived;
    if (steadyAnswer(prepared, r, uShifted, steady)) {
      prepared.project(steady);
      // Kept only when it answers the shifted problem within the tolerance: the one Newton step
      // on the last iteration's factors can miss it where W is nearly singular (the coplanar
      // points of a tower's base under a 1000:1 mass ratio: 3e-6 N s on one point, off the
      // weight by 3e-8), and the kept impulses are what a user reads as the contact forces.
      Eigen::VectorXd& uSteady = work.us;
      prepared.velocity(steady, uSteady);
      uSteady -= *arrived;
      if (prepared.residualFromVelocity(steady, uSteady) <= options.tolerance) {
        out.nextWarmStart = steady;
        out.hasNextWarmStart = true;
      }
    }
  }
  prepared.toOriginal(r, out.impulses);
  if (answerIsStickingStart && stepQ && stick.hasStepStart()) {
    // Projected like the start itself (body space is kept only for unscaled problems).
    out.nextWarmStart = stick.stepStart();
    prepared.project(out.nextWarmStart);
    out.hasNextWarmStart = true;
  }
  // The common residual: read from the solver's last evaluation when that was of this very answer
  // on the problem's own W (the same bits), else computed.
  const PreparedProblem::KnownEvaluation& end = prepared.end;
  const bool endIsAnswer = end.isOf(r) && prepared.scale.size() == 0 &&
                           (end.inBodySpace ? problem.W.bodySpaceOperator() != nullptr
                                            : problem.W.blockSparseMatrix() != nullptr);
  if (endIsAnswer) {
    out.velocities = end.u;
    report.residual = end.residual;
    report.absoluteResidual = end.absolute;
  } else {
    const ResidualValue res = commonResidual(problem, out.impulses, out.velocities);
    report.residual = res.relative;
    report.absoluteResidual = res.absolute;
  }
  if (ignoresStart() && report.iterations > 0 && report.status == SolverStatus::Converged) {
    // A direct solve that factorized: its own measure is this one (ignoresStart).
    context.record(report, report.iterations, report.residual);
    report.nativeResidual = report.residual;
    if (report.residual > options.tolerance) {
      report.status = SolverStatus::Stalled;
      report.note("direct solve above the tolerance (W ill-conditioned: redundant rows?)");
    }
  }
  // Never worse than the start, when asked (SolverOptions::neverWorseThanStart).
  if (options.neverWorseThanStart && report.residual > options.tolerance &&
      std::isfinite(report.residual) && r != r0) {
    prepared.toOriginal(r0, work.rs);
    const ResidualValue startResidual = commonResidual(problem, work.rs, work.us);
    if (startResidual.relative < report.residual) {
      std::ostringstream msg;
      msg << "answer's common residual " << report.residual << " above its start's "
          << startResidual.relative << ": the start is returned";
      report.note(msg.str());
      out.impulses.swap(work.rs);  // both keep their storage for the next solve
      out.velocities.swap(work.us);
      out.hasNextWarmStart = false;
      report.residual = startResidual.relative;
      report.absoluteResidual = startResidual.absolute;
    }
  }
  if (!std::isfinite(report.residual)) {  // cannot happen with finite r and a valid problem
    report.status = SolverStatus::NumericalFailure;
    out.impulses.setZero();
    out.velocities = problem.q;
    out.hasNextWarmStart = false;
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
  finish();
}

}  // namespace coulomb::solvers
