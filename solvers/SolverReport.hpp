#pragma once
// What every solve returns besides the impulses (docs/architecture.md golden rule 3): status,
// iterations, time, the common residual (1.8) measured after the last update, the solver's own
// measure, an optional history and a message saying what happened (regularization, fallbacks...).
#include <limits>
#include <string>
#include <string_view>
#include <vector>

namespace coulomb::solvers {

enum class SolverStatus {
  Converged,         // common residual <= tolerance
  MaxIterations,     // iteration or time budget spent (timeLimitReached says which)
  Stalled,           // no progress: the caller should try another solver (solveWithFallback)
  NumericalFailure,  // a non-finite value or singular system; the best finite iterate is returned
  InvalidProblem,    // validate() failed, or invalid options; the message names the problem
  NotApplicable      // the solver cannot handle this kind of problem (e.g. a block kind)
};

// "converged", "max_iterations", "stalled", "numerical_failure", "invalid_problem",
// "not_applicable" (the strings of the CLI's JSON lines).
const char* statusName(SolverStatus status);

struct IterationRecord {
  int iteration = 0;
  double seconds = 0.0;   // since the start of the solve
  double residual = 0.0;  // common e_rel of the iterate
};

struct SolverReport {
  std::string solver;  // registry name
  SolverStatus status = SolverStatus::NotApplicable;
  int iterations = 0;                                         // Newton steps or Gauss-Seidel sweeps
  double seconds = 0.0;                                       // wall clock of the whole solve
  double residual = std::numeric_limits<double>::infinity();  // common e_rel (1.8)
  double absoluteResidual = std::numeric_limits<double>::infinity();  // e_abs
  double nativeResidual = std::numeric_limits<double>::infinity();    // solver's own measure
  std::string nativeResidualName;                                     // what nativeResidual is
  bool timeLimitReached = false;
  int lineSearchFailures = 0;            // Newton: Goldstein-Price failures
  double maxRegularization = 0.0;        // Newton: largest sigma of (5.8) used [1/kg]
  std::vector<IterationRecord> history;  // when SolverOptions::recordHistory
  std::string message;                   // human-readable notes, "; "-separated

  void note(std::string_view text);  // appends to message (a literal makes no temporary string)
  // Back to a fresh report, keeping the strings' and the history's storage (solvers reuse one);
  // SolverReport.cpp resets field by field: a new field goes there too.
  void reset();
  [[nodiscard]] bool converged() const { return status == SolverStatus::Converged; }
};

}  // namespace coulomb::solvers
