#pragma once
// lemke: the contact problem as one LCP on the faceted (polyhedral) friction cone and Lemke's
// pivoting on it (docs/solver-derivations.md section 7; Stewart, Trinkle, IJNME 39 1996; Anitescu,
// Potra, Nonlinear Dyn. 14 1997; BET14 eqs. 49-52). Per contact, n_d friction directions d_k (7.1)
// with the slack row lambda of the Stewart-Trinkle / Anitescu-Potra formulation (7.2), layout
// (7.3); unilateral rows as plain LCP rows; bounded rows by the box form (7.6); equality rows (and
// bounded rows without finite bounds) eliminated by a Schur complement (7.5).
// The faceted friction is too small by up to cos(pi / n_d) and snaps sliding directions to the
// facets, so the report gives both the native LCP error and the common exact-cone residual (7.4).
// Ray termination (7.7) and the pivot limit are statuses (Stalled, MaxIterations) with the reason
// in the message; the answer is then the last basis (finite, in the cone). The LCP is built from
// W / s and q / s, s = max diag W (same r; the tableau's entries are O(1) whatever the units), and
// solved on a perturbed right-hand side (LemkeSettings::perturbation; docs/solvers.md "Lemke on
// redundant contacts").
#include <coulomb/solvers/ContactSolver.hpp>
#include <coulomb/solvers/lemke/LemkeLcp.hpp>

namespace coulomb::solvers {

struct LemkeOptions {
  // [directions] friction directions per contact (even, >= 4). Default 8: e_abs at the worst
  // sliding angle falls as n_d^-2 (0.131, 0.034, 0.0086 for 4, 8, 16; docs/solver-derivations.md
  // (7.4)) while the LCP grows by n_d + 2 per contact.
  int frictionDirections = 8;
  // [LCP unknowns] largest LCP taken; beyond it the solver reports NotApplicable (dense tableau of
  // 2 size^2 doubles, O(size^3) work). Default 1500, about 150 contacts at n_d = 8
  // (docs/solver-derivations.md 7).
  int maxLcpSize = 1500;
  // [-] Equality-block regularization eps * max diag(W_ff) added before the Schur elimination
  // (redundant joint rows, docs/solver-derivations.md 10). Default 1e-10 (the role of ODE's CFM).
  double equalityRegularization = 1e-10;
  // Pivot limit (0 = max(50, 10 size)), lexicographic anti-cycling, tolerances. The common
  // SolverOptions::maxIterations only raises the pivot limit (a path cut short has no answer).
  LemkeSettings lemke;
};

class LemkeSolver final : public ContactSolver {
 public:
  explicit LemkeSolver(LemkeOptions options = {}) : options_(options) {}
  [[nodiscard]] std::string name() const override { return "lemke"; }
  [[nodiscard]] const LemkeOptions& options() const { return options_; }
  [[nodiscard]] std::optional<std::string> notApplicable(
      const ContactProblem& problem) const override;
  void solvePrepared(const PreparedProblem& problem, const SolveContext& context,
                     Eigen::VectorXd& r, SolverReport& report) const override;

 private:
  LemkeOptions options_;
};

}  // namespace coulomb::solvers
