#include <coulomb/solvers/SolverChooser.hpp>

#include <algorithm>
#include <cmath>

namespace coulomb::solvers {
namespace {

// W_ii of the normal rows, when it is cheap (dense or block-sparse over the problem's blocks):
// which of W's forms holds them is looked up once per problem, not once per contact.
class NormalDiagonal {
 public:
  explicit NormalDiagonal(const ContactProblem& problem) {
    const auto blocks = static_cast<int>(problem.blocks.size());
    dense_ = problem.W.denseMatrix();
    if (dense_ != nullptr) return;
    if (const BodySpaceDelassus* body = problem.W.bodySpaceOperator()) {
      if (body->blockCount() == blocks) body_ = body;
      return;
    }
    const BlockSparseMatrix* sparse = problem.W.blockSparseMatrix();
    if (sparse != nullptr && sparse->blockCount() == blocks) sparse_ = sparse;
  }
  // W_ii of row `row`, the first of block `block`; false when W does not hold it cheaply.
  bool at(int row, int block, double& value) const {
    if (dense_ != nullptr) {
      value = (*dense_)(row, row);
      return true;
    }
    if (body_ != nullptr) {
      value = body_->diagonalBlocks()[9 * static_cast<std::size_t>(block)];  // cached W_bb
      return true;
    }
    if (sparse_ == nullptr) return false;
    const int k = sparse_->diagonalBlock(block);
    if (k < 0) return false;
    value = sparse_->blockValues(k)[0];
    return true;
  }

 private:
  const Eigen::MatrixXd* dense_ = nullptr;
  const BodySpaceDelassus* body_ = nullptr;
  const BlockSparseMatrix* sparse_ = nullptr;
};

}  // namespace

ProblemFeatures measureProblemFeatures(const ContactProblem& problem,
                                       const IslandFeatures& island) {
  ProblemFeatures f;
  f.unknowns = problem.size();
  f.degreesOfFreedom = island.degreesOfFreedom;
  f.zeroIsExact = true;
  f.factored = problem.W.bodySpaceOperator() != nullptr;
  double minW = std::numeric_limits<double>::infinity(), maxW = 0.0;
  const NormalDiagonal normalDiagonal(problem);
  bool diagonalKnown = true;
  int row = 0;  // first row of block b
  for (size_t b = 0; b < problem.blocks.size(); row += problem.blocks[b++].size()) {
    const ConstraintBlock& block = problem.blocks[b];
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
    // Active: approaching (q_N < 0), resting (q_N = 0: touching bodies moving together, as every
    // contact above the ground row of a fresh stack; they carry the load once it reaches them)
    // or loaded at the last step (warm start). Only separating contacts are left out.
    const bool warm = problem.warmStart && (*problem.warmStart)[row] > 0;
    f.warmStarted = f.warmStarted || warm;
    if (!(qN <= 0 || warm)) continue;
    ++f.activeContacts;
    double w = 0;
    if (diagonalKnown && normalDiagonal.at(row, static_cast<int>(b), w) && w > 0) {
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

void SolverChooser::choose(const ContactProblem& problem, const IslandFeatures& island,
                           const SolverChoice& choice, const SolverOptions& options,
                           SolvePlan& plan) const {
  plan.features = measureProblemFeatures(problem, island);
  plan.options = options;
  plan.promoted = false;
  plan.attempts.clear();
  if (choice.mode == ChoiceMode::Exactly) {  // the user's own chain, with the user's limits
    plan.attempts.insert(plan.attempts.end(), choice.attempts.begin(), choice.attempts.end());
    plan.rule = PlanRule::Exactly;
    return;
  }
  automatic(plan.features, plan);
  if (choice.mode == ChoiceMode::Automatic) return;
  // Preferred: the named attempts first (with their own limits only), then the automatic plan's
  // other solvers as fallbacks with the common options.
  const std::size_t automaticCount = plan.attempts.size();
  for (std::size_t k = 0; k < automaticCount; ++k) {
    bool named = false;
    for (const SolveAttempt& a : choice.attempts)
      named = named || a.solver == plan.attempts[k].solver;
    plan.attempts[k] = named ? SolveAttempt{} : SolveAttempt{plan.attempts[k].solver};
  }
  std::erase_if(plan.attempts, [](const SolveAttempt& a) { return a.solver.empty(); });
  plan.attempts.insert(plan.attempts.begin(), choice.attempts.begin(), choice.attempts.end());
  plan.rule = PlanRule::Preferred;
}

void SolverChooser::automatic(const ProblemFeatures& f, SolvePlan& plan) const {
  auto set = [&plan](PlanRule rule, std::initializer_list<SolveAttempt> attempts) {
    plan.rule = rule;
    plan.attempts.assign(attempts);
  };
  const bool newtonSized = f.unknowns <= settings_.newtonMaxUnknowns;
  const int scalarRows = f.equalityRows + f.boundedRows + f.unilateralRows;
  if (f.unknowns == 0 || f.zeroIsExact) {
    // docs/solver-derivations.md section 9, first row: every contact separates or rests without
    // approaching, so r = 0 is exact; the solver returns at its start residual without iterating.
    return set(PlanRule::ZeroIsExact, {{"bgs"}});
  }
  if (f.contacts == 1 && scalarRows == 0)  // Algorithm 4.1: exact in one sweep
    return set(PlanRule::OneContact, {{"bgs"}, {"ac_newton"}});
  if (f.contacts == 0 && scalarRows == f.equalityRows && f.equalityRows > 0) {
    // Bilateral rows only (a joint island without limits or motors): the problem is the linear
    // system W r = -q; a sparse LDL^T solves it directly, in linear time when the joints form a
    // tree (Baraff 1996). A loop makes W singular: ac_newton (regularized) takes over.
    return set(PlanRule::EqualityRowsOnly, {{"ldlt"}, {"ac_newton"}, {"bgs"}});
  }
  if (f.contacts == 0 && newtonSized) {
    // Joint rows only (equalities, limits, motors, joint friction): with no cone the problem is a
    // linear system plus a few bounds, which Newton solves in 1-3 steps, while Gauss-Seidel
    // converges like a chain's slowest mode (a 10-link chain needed > 50 bgs sweeps per step).
    return set(PlanRule::JointRowsOnly, {{"ac_newton"}, {"bgs"}});
  }
  // Gauss-Seidel with conjugate-gradient momentum on stacks (docs/solvers.md, "nncg"): pgs sweeps
  // once the contacts carry last step's load (cheapest per step), bgs sweeps from a cold start,
  // where exact local solves carry the load up the stack in a tenth of the sweeps.
  const char* const gaussSeidel = f.warmStarted ? "nncg" : "bgs_nncg";
  if (!newtonSized) return set(PlanRule::LargeIsland, {{gaussSeidel}, {"pgs"}});
  if (!std::isnan(f.massRatio) && f.massRatio > settings_.newtonMassRatio)
    return set(PlanRule::MassRatio, {{"ac_newton"}, {"fb_newton"}, {"bgs"}});
  const bool pileByNu = !std::isnan(f.nu) && f.nu > settings_.pileNu;
  const bool pileBySize = std::isnan(f.nu) && f.contacts >= settings_.pileContactsWithoutDofs;
  if (pileByNu || pileBySize) {
    // Gauss-Seidel first on piles and towers (Kaplas: pgs 2.7x faster than ac_newton); Newton as
    // the fallback for the stacks where Gauss-Seidel stalls (BoxesStack).
    return set(pileByNu ? PlanRule::PileByNu : PlanRule::PileBySize,
               {{gaussSeidel, 0, settings_.pileStallSweeps}, {"ac_newton"}, {"bgs"}});
  }
  if (f.factored && settings_.factoredTrySweeps > 0)
    return set(PlanRule::FactoredTry,
               {{"bgs", settings_.factoredTrySweeps}, {"ac_newton"}, {"fb_newton"}});
  if (f.activeContacts <= settings_.smallActiveContacts)
    return set(PlanRule::FewActiveContacts,
               {{"bgs", settings_.smallTrySweeps}, {"ac_newton"}, {"fb_newton"}});
  set(PlanRule::WellPosed, {{"ac_newton"}, {"bgs"}, {"fb_newton"}});
}

}  // namespace coulomb::solvers
