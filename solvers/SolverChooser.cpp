#include <coulomb/solvers/SolverChooser.hpp>

#include <cstdio>

namespace coulomb::solvers {
namespace {

std::string format(const char* pattern, double a, double b) {
  char buffer[160];
  std::snprintf(buffer, sizeof buffer, pattern, a, b);
  return buffer;
}

}  // namespace

SolvePlan SolverChooser::choose(const ContactProblem& problem, const IslandFeatures& features,
                                const std::string& requested, const SolverOptions& options) const {
  SolvePlan plan;
  plan.options = options;
  if (requested != "auto") {
    plan.solvers = {requested};
    if (requested != "ac_newton") plan.solvers.push_back("ac_newton");
    if (requested != "bgs") plan.solvers.push_back("bgs");
    plan.reason = "requested " + requested;
    return plan;
  }
  const int contacts = problem.contactCount();
  const int dofs = features.degreesOfFreedom > 0 ? features.degreesOfFreedom : problem.size();
  const double nu = 3.0 * contacts / static_cast<double>(dofs);
  // SOLVERS.md section 9: Newton is fast and exact for nu <= 2 on moderate sizes; Gauss-Seidel
  // wins on piles and towers (nu > 2 or many contacts), with Newton as the fallback.
  if (nu <= 2.0 && problem.size() <= 3000) {
    plan.solvers = {"ac_newton", "bgs"};
    plan.reason = format("auto: nu = %.2f <= 2 with %.0f unknowns: ac_newton", nu, problem.size());
  } else {
    plan.solvers = {"bgs", "ac_newton"};
    plan.reason =
        format("auto: nu = %.2f, %.0f unknowns: bgs (pile/tower regime)", nu, problem.size());
  }
  return plan;
}

}  // namespace coulomb::solvers
