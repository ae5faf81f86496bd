#include <coulomb/solvers/SolverReport.hpp>

namespace coulomb::solvers {

const char* statusName(SolverStatus status) {
  switch (status) {
    case SolverStatus::Converged:
      return "converged";
    case SolverStatus::MaxIterations:
      return "max_iterations";
    case SolverStatus::Stalled:
      return "stalled";
    case SolverStatus::NumericalFailure:
      return "numerical_failure";
    case SolverStatus::InvalidProblem:
      return "invalid_problem";
    case SolverStatus::NotApplicable:
      return "not_applicable";
  }
  return "?";
}

void SolverReport::note(std::string_view text) {
  if (text.empty()) return;
  if (!message.empty()) message += "; ";
  message += text;
}

void SolverReport::reset() {
  // Field by field (a new field is reset here too): the strings and the history keep their
  // storage, so a steady solve allocates nothing; the numbers take a default report's values.
  const SolverReport fresh{};
  status = fresh.status;
  iterations = fresh.iterations;
  seconds = fresh.seconds;
  residual = fresh.residual;
  absoluteResidual = fresh.absoluteResidual;
  nativeResidual = fresh.nativeResidual;
  timeLimitReached = fresh.timeLimitReached;
  lineSearchFailures = fresh.lineSearchFailures;
  maxRegularization = fresh.maxRegularization;
  solver.clear();
  nativeResidualName.clear();
  message.clear();
  history.clear();
  // Solvers name their measure with literals of under 64 characters: with this capacity a reused
  // report takes any of them without allocating, whichever solver wrote it last.
  nativeResidualName.reserve(64);
}

}  // namespace coulomb::solvers
