#pragma once
// The interface of every contact solver. solve() is the same for all of them (non-virtual):
// validate the options and the problem, return at once when there is nothing to do, prepare the
// problem, choose the start (warm start or 0, whichever has the smaller residual), run the
// algorithm, then measure the common residual after the last update on the original problem and
// guarantee a finite answer (a numerical failure is a status, never a NaN); with
// SolverOptions::neverWorseThanStart (the World's) an answer above the tolerance with a larger
// common residual than the start is replaced by the start (status kept, with a note).
// A solver implements solvePrepared(); composite solvers (hybrid starts, fallbacks) call other
// solvers' solvePrepared() on the same PreparedProblem.
#include <coulomb/solvers/ContactProblem.hpp>
#include <coulomb/solvers/PreparedProblem.hpp>
#include <coulomb/solvers/SolverOptions.hpp>
#include <coulomb/solvers/SolverReport.hpp>
#include <coulomb/solvers/StickingStart.hpp>

#include <Eigen/Core>

#include <optional>
#include <string>

namespace coulomb::solvers {

struct SolveOutcome {
  Eigen::VectorXd impulses;    // r, problem.size() entries, always finite
  Eigen::VectorXd velocities;  // u = W r + q
  SolverReport report;
  // With hasNextWarmStart, the warm start to keep for the next step instead of r: when r is the
  // all-sticking start of a warm-started problem with ContactProblem::arrival, the same start for
  // q - J v_k (the impulses that hold the step's load, without the one-off removal of the velocity
  // error the last step left; docs/solvers.md "Sticking start"). The vector keeps its storage.
  Eigen::VectorXd nextWarmStart;
  bool hasNextWarmStart = false;
};

class ContactSolver {
 public:
  virtual ~ContactSolver() = default;
  [[nodiscard]] virtual std::string name() const = 0;
  // Why this solver cannot take the problem (e.g. unsupported block kinds), or nullopt.
  [[nodiscard]] virtual std::optional<std::string> notApplicable(const ContactProblem&) const {
    return std::nullopt;
  }

  // [sweeps] With SolverOptions::stickingStart and a warm start, a body-space solver (Gauss-Seidel)
  // that has not converged after this many sweeps tries the all-sticking start and continues from
  // it when its residual is smaller. A warm-started resting stack either converges in one or two
  // sweeps (the warm start already carries the load) or needs tens to hundreds (the load has to
  // move through the stack, one layer per sweep, which the sticking start does at once); after two
  // sweeps the restart wastes little. Measured on pyramid_20 and pyramid_10 against 1 and 3
  // (docs/benchmarks.md "Sticking restart").
  static constexpr int kStickingRestartSweeps = 2;

  // True for solvers whose solvePrepared() works on PreparedProblem::bodySpace (W never formed).
  [[nodiscard]] virtual bool worksInBodySpace() const { return false; }
  // True for solvers whose answer does not depend on the start (a direct factorization): no start
  // is computed for them beyond the warm start and r = 0, and their one answer is measured once,
  // by the common residual (also their native residual: solvePrepared leaves both to solve()).
  [[nodiscard]] virtual bool ignoresStart() const { return false; }
  // For a converged answer r (prepared variables, unscaled problem) whose u = W r + q is known:
  // the answer of the same problem with u shifted to `uShifted` (q - J v_k: the step's load
  // without the one-off removal of the velocity error the last step left), when the solver can
  // give it at little cost: Newton takes one step with the factors of its last iteration. False
  // when it cannot. Kept as the next step's warm start (docs/solvers.md "Steady warm start").
  [[nodiscard]] virtual bool steadyAnswer(const PreparedProblem& /*problem*/,
                                          const Eigen::VectorXd& /*r*/,
                                          const Eigen::VectorXd& /*uShifted*/,
                                          Eigen::VectorXd& /*out*/) const {
    return false;
  }

  [[nodiscard]] SolveOutcome solve(const ContactProblem& problem,
                                   const SolverOptions& options = {}) const;
  // Same, starting from `start` (original variables) instead of the problem's warm start.
  [[nodiscard]] SolveOutcome solve(const ContactProblem& problem, const SolverOptions& options,
                                   const Eigen::VectorXd& start) const;
  // The same into `out` (start: null for the problem's warm start), reusing its vectors and this
  // solver's workspace: a solve of a problem no larger than the last allocates nothing in
  // solve() itself (what the algorithm needs is the solver's own business). A solver instance
  // must not be used by two threads at once; a nested solve on the same instance uses a
  // workspace of its own.
  void solve(const ContactProblem& problem, const SolverOptions& options,
             const Eigen::VectorXd* start, SolveOutcome& out) const;

  // The algorithm. On entry r is a feasible start (prepared variables); on exit the best iterate
  // found, finite. Sets status, iterations, native residual and notes; solve() does the rest.
  virtual void solvePrepared(const PreparedProblem& problem, const SolveContext& context,
                             Eigen::VectorXd& r, SolverReport& report) const = 0;

 private:
  struct Workspace {
    PreparedProblem prepared;
    Eigen::VectorXd u, dv, r, s, dvs, r0;
    Eigen::VectorXd rs, us;  // the start in original variables and its u (never worse than it)
    StickingStart sticking;  // SolverOptions::stickingStart, unless a workspace is lent
    Eigen::VectorXd arrived, stepQ;  // J v_k and q - J v_k (ContactProblem::arrival)
  };
  void run(const ContactProblem& problem, const SolverOptions& options,
           const Eigen::VectorXd* start, SolveOutcome& out, Workspace& work) const;
  mutable Workspace workspace_;
  mutable bool busy_ = false;
};

}  // namespace coulomb::solvers
