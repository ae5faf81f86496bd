#pragma once
// Options common to every solver. Each solver family has its own typed struct next to it
// (pgs/PgsSolver.hpp: PgsOptions, bgs/BgsSolver.hpp: BgsOptions, newton/AcNewtonSolver.hpp:
// AcNewtonOptions, ...), passed to the solver's constructor: adding a solver never changes this
// file (docs/architecture.md golden rule 4: typed value structs, unit, default and reason per
// field).
#include <coulomb/solvers/ParallelLoop.hpp>

#include <Eigen/Core>

#include <limits>
#include <optional>
#include <string>

namespace coulomb::solvers {

class StickingStart;

// Forms the rows' velocities at the step's start, J v_k (problem.size() entries), for a problem
// whose W has its entries: the caller holds J (a body-space W forms them itself from
// ContactProblem::arrival). Asked only by a converged solve's steady warm start.
class ArrivalRowVelocities {
 public:
  virtual ~ArrivalRowVelocities() = default;
  virtual void form(Eigen::VectorXd& out) const = 0;
};

struct SolverOptions {
  // [-] Target of the common relative residual e_rel (docs/solver-derivations.md (1.8)). Default
  // 1e-8: the corpus target; a simulation step is visually exact far above it (1e-4..1e-6 are
  // common in games).
  double tolerance = 1e-8;
  // [iterations: Newton steps or Gauss-Seidel sweeps] 0 = the solver's own default (pgs, bgs:
  // 10000 sweeps like Siconos' NSGS; ac_newton: 200 like AC11 section 5.2). Lemke's pivot limit
  // is only raised by it, never lowered (LemkeOptions).
  int maxIterations = 0;
  // [s] Wall-clock budget, checked once per iteration (a Gauss-Seidel sweep, a Newton step):
  // a corpus run must never hang. Default: no limit (the step loop sets one when it needs to).
  double timeLimitSeconds = std::numeric_limits<double>::infinity();
  // Start from ContactProblem::warmStart when present (projected onto the constraint set and
  // kept only if its residual beats r = 0, docs/solver-derivations.md (3.6)). Default on: warm
  // starts are what make stacks cheap.
  bool useWarmStart = true;
  // Record (iteration, seconds, e_rel) after every iteration in SolverReport::history. Default off:
  // it costs one residual evaluation per iteration for solvers that do not compute it anyway.
  bool recordHistory = false;
  // [iterations] 0 = each solver's own stall test (pgs 5000 sweeps, bgs 2000). A positive value
  // shortens the Gauss-Seidel test to this window: stop (Stalled) when the best residual fell by
  // less than 1 % over it. The automatic plan gives pgs 20 sweeps before its Newton fallback
  // (ChooserSettings::pileStallSweeps): a pgs that stagnates just above the tolerance otherwise
  // spends its whole sweep cap before Newton takes over.
  int stallWindow = 0;
  // Never return an answer above the tolerance whose common residual is larger than that of the
  // start (the better of the projected warm start and r = 0): return the start instead, with the
  // solver's status and a note (ContactSolver::solve). What a simulation applies must be the
  // least-bad safe answer: a pivoting solver ignores its start and can end far from any answer
  // (issue 24: lemke on a cut path, residuals up to 1e13, bodies shot away). Default off, so that
  // a corpus run shows each solver's own answer; on in SolvePolicy::simulationOptions (the World).
  bool neverWorseThanStart = false;
  // [blocks] A Gauss-Seidel sweep (pgs, bgs and their nncg forms) over at least twice this many
  // blocks is split into parts of about this many blocks (at most 64; SweepPartition.hpp): the
  // parts' interiors run at once on the threads of `parallel`, then the blocks between parts,
  // coloured. The same bits on any number of threads; the split changes the order of the sweep
  // (its iterates, not the solution), so it is a setting of its own, never a consequence of the
  // thread count. 0 = never. Default 0 here (a captured problem is solved as before); the World
  // splits large islands (SolvePolicy::simulationOptions, docs/tuning.md).
  int sweepPartBlocks = 0;
  // The all-sticking start (StickingStart.hpp: every touching contact stopped, in body space,
  // O(bodies) on stacks) when W is held in body space (a World island): tried before the solver
  // when the problem has no warm start (a fresh stack, a landing box) and the start is above the
  // tolerance, and as a restart when a warm-started Gauss-Seidel solve has not converged after
  // ContactSolver::kStickingRestartSweeps sweeps; kept only when its residual is smaller. A
  // resting stack is then solved at its start instead of after hundreds of sweeps. Default off
  // here (a captured problem is solved as before); on in the World
  // (SolvePolicy::simulationOptions, docs/solvers.md "Sticking start").
  bool stickingStart = false;
  // The start sweep (StartSweep.hpp): a given or warm start above the tolerance, on a problem with
  // W's entries (not body space), is refined by one Gauss-Seidel sweep of exact local solves
  // before a solver that does not sweep itself (Newton) iterates; kept when its residual is
  // smaller, and the answer when within the tolerance. A resting box whose warm start drifted
  // past the tolerance is then solved by 3 x 3 solves instead of a Newton iteration. Default off
  // here (a captured problem is solved as before); on in the World
  // (SolvePolicy::simulationOptions, docs/solvers.md "Start sweep").
  bool startSweep = false;
  // Threads lent to this solve by the caller (the World passes its executor when
  // WorldSettings::threads > 1; not saved, not compared). Null: the calling thread only.
  ParallelLoop* parallel = nullptr;
  // The sticking start's workspace lent by the caller (solveWithFallback lends its
  // SolverInstances' one, shared by the attempts of an island: its ordering of the contact graph
  // carries over from the step that computed it to the solver instance that needs it next; not
  // saved, not compared). Null: the solver's own.
  StickingStart* stickingWorkspace = nullptr;
  // J v_k on demand, lent by the caller for this solve (the World, for its islands with W's
  // entries and no trees; not saved, not compared). Null: none, so no steady warm start there.
  const ArrivalRowVelocities* arrivalRows = nullptr;
};

// The first invalid field, or nullopt.
std::optional<std::string> validateOptions(const SolverOptions& options);

}  // namespace coulomb::solvers
