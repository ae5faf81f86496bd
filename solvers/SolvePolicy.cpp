#include <coulomb/solvers/SolvePolicy.hpp>
#include <coulomb/solvers/SolverRegistry.hpp>

#include <cmath>
#include <stdexcept>

namespace coulomb::solvers {

SolverChoice SolverChoice::preferred(std::string solver) {
  return {ChoiceMode::Preferred, {SolveAttempt{std::move(solver)}}};
}

SolverChoice SolverChoice::only(std::string solver) {
  return {ChoiceMode::Exactly, {SolveAttempt{std::move(solver)}}};
}

SolverChoice SolverChoice::chain(std::vector<std::string> solvers) {
  SolverChoice c{ChoiceMode::Exactly, {}};
  for (std::string& s : solvers) c.attempts.push_back(SolveAttempt{std::move(s)});
  return c;
}

std::string SolverChoice::text() const {
  if (mode == ChoiceMode::Automatic) return "auto";
  std::string out;
  for (const SolveAttempt& a : attempts) out += (out.empty() ? "" : ",") + a.solver;
  if (mode == ChoiceMode::Exactly && attempts.size() == 1) out += "!";
  return out;
}

std::optional<SolverChoice> parseSolverChoice(const std::string& text, std::string& error) {
  if (text == "auto") return SolverChoice::automatic();
  std::vector<std::string> names;
  std::string name;
  for (std::size_t i = 0; i <= text.size(); ++i) {
    if (i < text.size() && text[i] != ',') {
      name += text[i];
      continue;
    }
    if (name.empty()) {
      error = "empty solver name in '" + text + "' (expected \"auto\", NAME, NAME! or A,B,C)";
      return std::nullopt;
    }
    names.push_back(name);
    name.clear();
  }
  const bool alone = names.size() == 1 && names.front().back() == '!';
  for (std::size_t k = 0; k < names.size(); ++k) {
    const std::size_t bang = names[k].find('!');
    if (bang == std::string::npos) continue;
    if (!alone || bang + 1 != names[k].size() || names[k].size() == 1) {
      error = "'!' only ends a single solver name (NAME!), not '" + text + "'";
      return std::nullopt;
    }
  }
  if (alone) return SolverChoice::only(names.front().substr(0, names.front().size() - 1));
  if (names.size() == 1) return SolverChoice::preferred(names.front());
  return SolverChoice::chain(std::move(names));
}

SolverChoice solverChoice(const std::string& text) {
  std::string error;
  std::optional<SolverChoice> choice = parseSolverChoice(text, error);
  if (!choice) throw std::invalid_argument(error);
  return *choice;
}

std::optional<std::string> unknownSolver(const SolverChoice& choice,
                                         const SolverRegistry& registry) {
  for (const SolveAttempt& a : choice.attempts)
    if (!registry.find(a.solver)) return a.solver;
  return std::nullopt;
}

std::optional<std::string> SolvePolicy::validate(const SolverRegistry* registry) const {
  if (choice.mode != ChoiceMode::Automatic && choice.attempts.empty())
    return "solver: a named or chained choice needs at least one attempt";
  if (choice.mode == ChoiceMode::Automatic && !choice.attempts.empty())
    return "solver: an automatic choice has no attempts of its own";
  if (auto unknown = registry ? unknownSolver(choice, *registry) : std::nullopt) {
    std::string known;
    for (const std::string& n : registry->names()) known += (known.empty() ? "" : ", ") + n;
    return "solver: unknown solver '" + *unknown + "' (known: " + known + ")";
  }
  for (const SolveAttempt& a : choice.attempts)
    if (a.maxIterations < 0 || a.stallWindow < 0 || !(a.tolerance >= 0.0) ||
        !std::isfinite(a.tolerance))
      return "solver: attempt '" + a.solver +
             "': max_iterations, stall_window and tolerance must be >= 0 and finite";
  if (auto bad = validateOptions(options)) return "solver options: " + *bad;
  const ChooserSettings& c = chooser;
  if (!(c.pileNu > 0.0) || !std::isfinite(c.pileNu) || c.newtonMaxUnknowns < 0 ||
      c.pileContactsWithoutDofs < 0 || c.smallActiveContacts < 0 || c.smallTrySweeps < 0 ||
      c.factoredTrySweeps < 0 || !(c.newtonMassRatio >= 1.0) || c.pileStallSweeps < 0)
    return "solver chooser: thresholds must be >= 0 (pile_nu > 0, newton_mass_ratio >= 1)";
  const PromotionRule& p = promotion;
  if (!(p.nearMiss >= 1.0) || !std::isfinite(p.nearMiss) || p.iterationCap < 1 ||
      !(p.toleranceScale > 0.0 && p.toleranceScale <= 1.0) || p.minUnknowns < 0)
    return "solver promotion: near_miss >= 1, iteration_cap >= 1, tolerance_scale in (0, 1], "
           "min_unknowns >= 0";
  return std::nullopt;
}

}  // namespace coulomb::solvers
