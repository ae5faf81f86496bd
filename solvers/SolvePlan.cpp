#include <coulomb/solvers/SolvePlan.hpp>

#include <cmath>
#include <sstream>

namespace coulomb::solvers {

const char* planRuleName(PlanRule rule) {
  switch (rule) {
    case PlanRule::ZeroIsExact:
      return "all q_N >= 0 and no equality or bounded rows: r = 0 is exact";
    case PlanRule::OneContact:
      return "one contact: bgs solves it exactly in one sweep";
    case PlanRule::EqualityRowsOnly:
      return "equality rows only: a sparse LDL^T solve, ac_newton as the fallback";
    case PlanRule::JointRowsOnly:
      return "joint rows only: ac_newton, Gauss-Seidel converges slowly";
    case PlanRule::LargeIsland:
      return "large island: nncg, no Newton beyond newton_max_unknowns";
    case PlanRule::MassRatio:
      return "mass ratio above newton_mass_ratio: Newton, Gauss-Seidel stagnates";
    case PlanRule::PileByNu:
      return "pile or tower by nu: nncg, then ac_newton";
    case PlanRule::PileBySize:
      return "large island, dofs unknown: nncg, then ac_newton";
    case PlanRule::FactoredTry:
      return "body-space W: a short bgs try, then ac_newton";
    case PlanRule::FewActiveContacts:
      return "few active contacts: a short bgs try, then ac_newton";
    case PlanRule::WellPosed:
      return "well-posed enough for Newton: ac_newton";
    case PlanRule::Preferred:
      return "requested solver first, fallbacks of the automatic plan";
    case PlanRule::Exactly:
      return "requested solver(s) alone";
  }
  return "?";
}

std::string SolvePlan::reason() const {
  const ProblemFeatures& f = features;
  std::ostringstream s;
  const bool automatic = rule != PlanRule::Preferred && rule != PlanRule::Exactly;
  s << (automatic ? "auto: " : "") << planRuleName(rule) << " (" << f.contacts << " contacts ("
    << f.activeContacts << " active)";
  const int rows = f.equalityRows + f.boundedRows + f.unilateralRows;
  if (rows > 0) s << ", " << rows << " scalar rows (" << f.equalityRows << " equality)";
  if (!std::isnan(f.nu)) s << ", nu = " << std::round(f.nu * 100) / 100;
  if (!std::isnan(f.massRatio)) s << ", kappa = " << static_cast<float>(f.massRatio);
  s << ", " << f.unknowns << " unknowns); attempts:";
  for (const SolveAttempt& a : attempts) {
    s << " " << a.solver;
    if (a.maxIterations > 0) s << " cap " << a.maxIterations;
    if (a.stallWindow > 0) s << " stall " << a.stallWindow;
    if (a.tolerance > 0) s << " tol " << a.tolerance;
  }
  if (promoted)
    s << "; " << attempts.front().solver << " first: it finished this island's last step";
  return s.str();
}

SolverOptions SolvePlan::optionsFor(const SolveAttempt& attempt) const {
  SolverOptions o = options;
  if (attempt.maxIterations > 0) o.maxIterations = attempt.maxIterations;
  if (attempt.stallWindow > 0) o.stallWindow = attempt.stallWindow;
  if (attempt.tolerance > 0) o.tolerance = attempt.tolerance;
  return o;
}

}  // namespace coulomb::solvers
