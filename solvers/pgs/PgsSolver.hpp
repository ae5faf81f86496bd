#pragma once
// pgs: projected Gauss-Seidel / PSOR with the exact per-contact cone (docs/solver-derivations.md
// section 3), never a box or a pyramid.
#include <coulomb/solvers/ContactSolver.hpp>
#include <coulomb/solvers/GaussSeidelLoop.hpp>

#include <cstdint>

#include <vector>

namespace coulomb::solvers {

struct PgsOptions {
  enum class Update {
    // (3.3) r_c <- P_K(r_c - rho_c (u_c + mu ||u_T|| e_N)), rho_c = 1/lambda_max(sym W_cc):
    // one fixed-point step of (1.7) on the contact. Default: it solved 26/30 corpus problems in
    // the prototypes, and it is a scalar step, so slip directions are right (pitfall 7).
    ConeProjection,
    // (3.2) normal first, r_N <- [r_N - u_N/W_NN]_+, then r_T <- P_D(mu r_N)(r_T - rho_T u_T) with
    // the scalar rho_T = 1/lambda_max(sym W_TT): the game-engine update with the exact disk.
    NormalThenTangent
  };
  Update update = Update::ConeProjection;
  // [-] PSOR relaxation omega in (0, 2), step relaxed then projected (3.5). Default 1: SOR theory
  // covers only symmetric LCPs; on frictional problems omega > 1 may diverge.
  double omega = 1.0;
  // Visit order reshuffled every sweep with a local RNG seeded by `seed` (deterministic). Default
  // off: the fixed order (block ids) is deterministic without a seed and as fast on the corpus.
  bool shuffle = false;
  std::uint64_t seed = 0;
  // Nonsmooth nonlinear conjugate gradient (the registry's `nncg`; Silcowski, Erleben et al.
  // 2015, Algorithm 2, on these very sweeps): momentum from the last sweeps' steps after every
  // sweep, so the slow, smooth modes of a stack converge in hundreds of sweeps instead of
  // thousands (GaussSeidelSettings::conjugateGradient). Off for `pgs` itself.
  bool conjugateGradient = false;
  // [sweeps] stall test window: stop (Stalled) when the best residual fell by < 1 % over it.
  // Default 5000, not the 500 of Algorithm 3.1: pgs crosses plateaus of several thousand sweeps
  // on the Capsules stacks before converging (measured, docs/solvers.md).
  int stallWindow = 5000;
  // [sweeps] between two residual checks; 0 = auto: every sweep for 20 sweeps, then every 2..5
  // (a check costs about one sweep).
  int residualInterval = 0;
};

class PgsSolver final : public ContactSolver {
 public:
  explicit PgsSolver(PgsOptions options = {}) : options_(options) {}
  [[nodiscard]] std::string name() const override {
    return options_.conjugateGradient ? "nncg" : "pgs";
  }
  [[nodiscard]] bool worksInBodySpace() const override { return true; }
  [[nodiscard]] const PgsOptions& options() const { return options_; }
  void solvePrepared(const PreparedProblem& problem, const SolveContext& context,
                     Eigen::VectorXd& r, SolverReport& report) const override;

 private:
  struct Local {  // per contact block: W_bb and its steps
    Eigen::Matrix3d W;
    double rho = 0, rhoN = 0, rhoT = 0;
  };
  PgsOptions options_;
  mutable std::vector<Local> local_;  // kept for their storage (see ContactSolver::solve)
  mutable GaussSeidelWorkspace workspace_;
};

// 1 / lambda_max((A + A^T)/2) of a 3x3 block, and of its tangential 2x2 block; used for the
// scalar steps of (3.2), (3.3), (4.6) and the spectral rho of (5.14). Returns 0 when not positive.
double inverseSpectralRadius(const Eigen::Matrix3d& block);
double inverseTangentSpectralRadius(const Eigen::Matrix3d& block);

}  // namespace coulomb::solvers
