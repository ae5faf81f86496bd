#pragma once
// THE common residual every solver reports (docs/architecture.md section 4,
// docs/solver-derivations.md (1.8), (10.1)):
//   contact c:  F_c = r_c - P_K(r_c - (u_c + mu ||u_T,c|| e_N))     (natural map, rho = 1)
//   scalar i:   F_i = r_i - P_C(r_i - u_i)      (C = R, [lo, hi] or [0, inf))
//   e_abs = sqrt(sum ||F||^2),  e_rel = e_abs / (1 + ||q||),  u = W r + q recomputed here.
// For a pure contact problem with block-sparse W this is bit-identical to
// fc3d_natural_map_residual (same products in the same order). Anisotropic contacts use the
// Euclidean projection on their elliptic cone and the shift ||(mu1 u_T1, mu2 u_T2)||.
#include <coulomb/solvers/ContactProblem.hpp>

#include <Eigen/Core>

#include <vector>

namespace coulomb::solvers {

struct ResidualValue {
  double absolute = 0.0;  // e_abs
  double relative = 0.0;  // e_rel = e_abs / (1 + ||q||), the number reported everywhere
};

// sqrt(sum q_i^2) accumulated in index order (as fc3d_norm).
double plainNorm(const Eigen::VectorXd& v);

// Adds the squared natural-map components of one block (r, u: pointers to size() values) to sum.
void accumulateBlockResidual(const ConstraintBlock& block, const double* r, const double* u,
                             double& sum);
// The same, alone.
double blockResidualSquared(const ConstraintBlock& block, const double* r, const double* u);

// e_abs from r and u = W r + q (u supplied by the caller, who must have recomputed it).
double residualFromVelocity(const std::vector<ConstraintBlock>& blocks, const Eigen::VectorXd& r,
                            const Eigen::VectorXd& u);

// e_abs^2's part over blocks [first, last), whose first unknown is at `offset` (the pieces of a
// split sweep's check, summed in block order by the caller).
double residualSquares(const std::vector<ConstraintBlock>& blocks, int first, int last, int offset,
                       const Eigen::VectorXd& r, const Eigen::VectorXd& u);

// The common residual of r for the problem: computes u = W r + q, then (1.8).
ResidualValue commonResidual(const ContactProblem& problem, const Eigen::VectorXd& r);
ResidualValue commonResidual(const ContactProblem& problem, const Eigen::VectorXd& r,
                             Eigen::VectorXd& u);  // also returns u

}  // namespace coulomb::solvers
