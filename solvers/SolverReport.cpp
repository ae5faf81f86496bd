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
  std::string keptSolver = std::move(solver), keptName = std::move(nativeResidualName),
              keptMessage = std::move(message);
  std::vector<IterationRecord> keptHistory = std::move(history);
  *this = SolverReport{};
  keptSolver.clear();
  keptName.clear();
  keptMessage.clear();
  keptHistory.clear();
  solver = std::move(keptSolver);
  nativeResidualName = std::move(keptName);
  // Solvers name their measure with literals of under 64 characters: with this capacity a reused
  // report takes any of them without allocating, whichever solver wrote it last.
  nativeResidualName.reserve(64);
  message = std::move(keptMessage);
  history = std::move(keptHistory);
}

}  // namespace coulomb::solvers
