#include <coulomb/solvers/SolverChooser.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

namespace coulomb::solvers {
namespace {

// W_ii of the normal rows, when it is cheap (dense or block-sparse over the problem's blocks).
bool normalDiagonal(const ContactProblem& problem, const std::vector<int>& offsets, int block,
                    double& value) {
  const int row = offsets[block];
  if (const Eigen::MatrixXd* dense = problem.W.denseMatrix()) {
    value = (*dense)(row, row);
    return true;
  }
  if (const BodySpaceDelassus* body = problem.W.bodySpaceOperator()) {
    if (body->blockCount() != static_cast<int>(problem.blocks.size())) return false;
    value = body->diagonalBlocks()[9 * static_cast<std::size_t>(block)];  // cached W_bb
    return true;
  }
  const BlockSparseMatrix* sparse = problem.W.blockSparseMatrix();
  if (!sparse || sparse->blockCount() != static_cast<int>(problem.blocks.size())) return false;
  const int k = sparse->diagonalBlock(block);
  if (k < 0) return false;
  value = sparse->blockValues(k)[0];
  return true;
}

std::string describe(const ProblemFeatures& f) {
  std::ostringstream s;
  s << f.contacts << " contacts (" << f.activeContacts << " active)";
  const int rows = f.equalityRows + f.boundedRows + f.unilateralRows;
  if (rows > 0) s << ", " << rows << " scalar rows (" << f.equalityRows << " equality)";
  if (!std::isnan(f.nu)) s << ", nu = " << std::round(f.nu * 100) / 100;
  if (!std::isnan(f.massRatio)) s << ", kappa = " << static_cast<float>(f.massRatio);
  s << ", " << f.unknowns << " unknowns";
  return s.str();
}

std::vector<std::string> splitChain(const std::string& text) {
  std::vector<std::string> names;
  std::stringstream s(text);
  std::string name;
  while (std::getline(s, name, ','))
    if (!name.empty()) names.push_back(name);
  return names;
}

}  // namespace

ProblemFeatures measureProblemFeatures(const ContactProblem& problem,
                                       const IslandFeatures& island) {
  ProblemFeatures f;
  f.unknowns = problem.size();
  f.degreesOfFreedom = island.degreesOfFreedom;
  f.zeroIsExact = true;
  f.factored = problem.W.bodySpaceOperator() != nullptr;
  const std::vector<int> offsets = problem.blockOffsets();
  double minW = std::numeric_limits<double>::infinity(), maxW = 0.0;
  bool diagonalKnown = true;
  for (size_t b = 0; b < problem.blocks.size(); ++b) {
    const ConstraintBlock& block = problem.blocks[b];
    const int row = offsets[b];
    const double qN = problem.q[row];
    switch (block.kind) {
      case BlockKind::Equality:
        ++f.equalityRows;
        f.zeroIsExact = false;
        continue;
      case BlockKind::Bounded:
        ++f.boundedRows;
        f.zeroIsExact = false;
        continue;
      case BlockKind::Unilateral:
        ++f.unilateralRows;
        f.zeroIsExact = f.zeroIsExact && qN >= 0;
        continue;
      case BlockKind::Contact3D:
        break;
    }
    ++f.contacts;
    f.zeroIsExact = f.zeroIsExact && qN >= 0;
    const bool warm = problem.warmStart && (*problem.warmStart)[row] > 0;
    if (!(qN < 0 || warm)) continue;
    ++f.activeContacts;
    double w = 0;
    if (diagonalKnown && normalDiagonal(problem, offsets, static_cast<int>(b), w) && w > 0) {
      minW = std::min(minW, w);
      maxW = std::max(maxW, w);
    } else {
      diagonalKnown = false;
    }
  }
  if (diagonalKnown && f.activeContacts > 0) f.massRatio = maxW / minW;
  if (island.degreesOfFreedom > 0) {
    const int rows = f.equalityRows + f.boundedRows + f.unilateralRows;
    f.nu = (3.0 * f.activeContacts + rows) / island.degreesOfFreedom;
  }
  return f;
}

SolvePlan SolverChooser::choose(const ContactProblem& problem, const IslandFeatures& island,
                                const std::string& requested, const SolverOptions& options) const {
  const ProblemFeatures features = measureProblemFeatures(problem, island);
  SolvePlan plan = automatic(features);
  plan.options = options;
  plan.features = features;
  if (requested == "auto" || requested.empty()) {
    plan.reason = "auto: " + plan.reason;
    return plan;
  }
  plan.iterationCaps.clear();  // a user's choice runs with the user's options
  plan.stallWindows.clear();
  if (requested.find(',') != std::string::npos) {  // the user's own chain
    plan.solvers = splitChain(requested);
    plan.reason = "requested chain " + requested;
    return plan;
  }
  if (requested.back() == '!') {  // one solver, no fallback
    plan.solvers = {requested.substr(0, requested.size() - 1)};
    plan.reason = "requested " + plan.solvers.front() + " alone";
    return plan;
  }
  // A named solver first, then the automatic plan's solvers as fallbacks.
  std::vector<std::string> chain{requested};
  for (const std::string& name : plan.solvers)
    if (name != requested) chain.push_back(name);
  plan.solvers = chain;
  plan.reason = "requested " + requested + " (fallbacks of the automatic plan)";
  return plan;
}

SolvePlan SolverChooser::automatic(const ProblemFeatures& f) const {
  SolvePlan plan;
  const std::string what = describe(f);
  const bool newtonSized = f.unknowns <= settings_.newtonMaxUnknowns;
  const int scalarRows = f.equalityRows + f.boundedRows + f.unilateralRows;
  if (f.unknowns == 0 || f.zeroIsExact) {
    // SOLVERS.md section 9, first row: every contact separates or rests without approaching, so
    // r = 0 is exact; the solver returns at its start residual without iterating.
    plan.solvers = {"bgs"};
    plan.reason = "all q_N >= 0 and no equality or bounded rows: r = 0 is exact (" + what + ")";
    return plan;
  }
  if (f.contacts == 1 && scalarRows == 0) {
    plan.solvers = {"bgs", "ac_newton"};
    plan.reason = "one contact: bgs solves it exactly in one sweep (Algorithm 4.1)";
    return plan;
  }
  if (f.contacts == 0 && newtonSized) {
    // Joint rows only (equalities, limits, motors, joint friction): with no cone the problem is a
    // linear system plus a few bounds, which Newton solves in 1-3 steps, while Gauss-Seidel
    // converges like a chain's slowest mode (a 10-link chain needed > 50 bgs sweeps per step).
    plan.solvers = {"ac_newton", "bgs"};
    plan.reason = "joint rows only (" + what + "): ac_newton, Gauss-Seidel converges slowly";
    return plan;
  }
  if (!newtonSized) {
    plan.solvers = {"bgs", "pgs"};
    plan.reason = "large island (" + what + "): bgs, no Newton beyond " +
                  std::to_string(settings_.newtonMaxUnknowns) + " unknowns";
    return plan;
  }
  const bool heavyRatio = !std::isnan(f.massRatio) && f.massRatio > settings_.newtonMassRatio;
  if (heavyRatio) {
    plan.solvers = {"ac_newton", "fb_newton", "bgs"};
    plan.reason = "mass ratio above " +
                  std::to_string(static_cast<int>(settings_.newtonMassRatio)) + " (" + what +
                  "): Newton, Gauss-Seidel stagnates";
    return plan;
  }
  const bool pileByNu = !std::isnan(f.nu) && f.nu > settings_.pileNu;
  const bool pileBySize = std::isnan(f.nu) && f.contacts >= settings_.pileContactsWithoutDofs;
  if (pileByNu || pileBySize) {
    // Gauss-Seidel first on piles and towers (Kaplas: pgs 2.7x faster than ac_newton); Newton as
    // the fallback for the stacks where Gauss-Seidel stalls (BoxesStack).
    plan.solvers = {"pgs", "ac_newton", "bgs"};
    plan.stallWindows = {settings_.pileStallSweeps};
    plan.reason = std::string(pileByNu ? "pile or tower by nu" : "large island, dofs unknown") +
                  " (" + what + "): pgs, then ac_newton";
    return plan;
  }
  if (f.factored && settings_.factoredTrySweeps > 0) {
    plan.solvers = {"bgs", "ac_newton", "fb_newton"};
    plan.iterationCaps = {settings_.factoredTrySweeps};
    plan.reason = "body-space W (" + what + "): " + std::to_string(settings_.factoredTrySweeps) +
                  " bgs sweeps, then ac_newton";
    return plan;
  }
  if (f.activeContacts <= settings_.smallActiveContacts) {
    plan.solvers = {"bgs", "ac_newton", "fb_newton"};
    plan.iterationCaps = {settings_.smallTrySweeps};
    plan.reason = "few active contacts (" + what +
                  "): " + std::to_string(settings_.smallTrySweeps) + " bgs sweeps, then ac_newton";
    return plan;
  }
  plan.solvers = {"ac_newton", "bgs", "fb_newton"};
  plan.reason = "well-posed enough for Newton (" + what + "): ac_newton";
  return plan;
}

}  // namespace coulomb::solvers
