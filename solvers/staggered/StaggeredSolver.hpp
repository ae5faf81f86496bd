#pragma once
// staggered: staggered projections (Kaufman, Sueda, James, Pai, ACM TOG 27(5) 2008; BET14 section
// 4.2.3; docs/solver-derivations.md section 8, Algorithm 8.1): alternate the normal QP (8.1) with
// the friction fixed and the friction QP (8.2) with the normals (hence the disk radii mu r_N)
// fixed, until the fixed point, which satisfies the exact Coulomb law. Both QPs by APGD
// (Algorithm 8.2: Nesterov acceleration, Lipschitz backtracking (8.5), adaptive restart (8.7) of
// O'Donoghue and Candes 2015), using W's blocks as they are (non-symmetric W: a heuristic for the
// monotone VI, judged by the residual, docs/solver-derivations.md section 8). Equality, bounded and
// unilateral rows join the normal step (docs/solver-derivations.md 10). Reports outer iterations
// and the total inner APGD iterations.
#include <coulomb/solvers/ContactSolver.hpp>

namespace coulomb::solvers {

struct StaggeredOptions {
  // [outer iterations] default when SolverOptions::maxIterations is 0. Default 1000: linear outer
  // convergence, median 33 on well-posed random problems, up to 329 on OneObject
  // (docs/solver-derivations.md 8).
  int defaultMaxOuter = 1000;
  // [APGD iterations] per QP. Default 500 (median 54, max 251 on random QPs,
  // docs/solver-derivations.md (8.3)).
  int maxInner = 500;
  // [power iterations] for lambda_max(sym A) in (8.3). Default 20.
  int powerIterations = 20;
  // Adaptive restart (8.7). Default on: without it APGD oscillates on ill-conditioned stacks.
  bool restart = true;
  // [outer iterations] Stalled when the best e_rel fell by < 1 % over this many. Default 200.
  int stallWindow = 200;
};

class StaggeredSolver final : public ContactSolver {
 public:
  explicit StaggeredSolver(StaggeredOptions options = {}) : options_(options) {}
  [[nodiscard]] std::string name() const override { return "staggered"; }
  [[nodiscard]] const StaggeredOptions& options() const { return options_; }
  void solvePrepared(const PreparedProblem& problem, const SolveContext& context,
                     Eigen::VectorXd& r, SolverReport& report) const override;

 private:
  StaggeredOptions options_;
};

}  // namespace coulomb::solvers
