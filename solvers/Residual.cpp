#include <coulomb/solvers/Residual.hpp>

#include <coulomb/solvers/CoulombLaw.hpp>

#include <algorithm>
#include <cmath>

namespace coulomb::solvers {

double plainNorm(const Eigen::VectorXd& v) {
  double s = 0;
  for (Eigen::Index i = 0; i < v.size(); ++i) s += v[i] * v[i];
  return std::sqrt(s);
}

// Term by term into the running sum, in the order of fc3d_natural_map_residual (tests/data/fc3d):
// the total agrees with the reference to round-off (tangentNorm for its std::hypot).
void accumulateBlockResidual(const ConstraintBlock& block, const double* r, const double* u,
                             double& sum) {
  switch (block.kind) {
    case BlockKind::Contact3D: {
      if (block.anisotropic) {
        const Eigen::Vector3d rc(r[0], r[1], r[2]), uc(u[0], u[1], u[2]);
        const Eigen::Vector3d p = projectOntoEllipticCone(
            rc - deSaxceShift(uc, block.mu1, block.mu2), block.mu1, block.mu2);
        for (int k = 0; k < 3; ++k) sum += (rc[k] - p[k]) * (rc[k] - p[k]);
        return;
      }
      double x[3] = {r[0] - (u[0] + block.mu * tangentNorm(u[1], u[2])), r[1] - u[1], r[2] - u[2]};
      projectOntoCone(x, block.mu);
      for (int k = 0; k < 3; ++k) sum += (r[k] - x[k]) * (r[k] - x[k]);
      return;
    }
    case BlockKind::Equality:
      sum += u[0] * u[0];
      return;  // P_R = identity: F = u
    case BlockKind::Unilateral: {
      const double f = r[0] - std::max(r[0] - u[0], 0.0);  // = min(r, u)
      sum += f * f;
      return;
    }
    case BlockKind::Bounded: {
      const double f = r[0] - std::clamp(r[0] - u[0], block.lower, block.upper);
      sum += f * f;
      return;
    }
  }
}

double blockResidualSquared(const ConstraintBlock& block, const double* r, const double* u) {
  double s = 0;
  accumulateBlockResidual(block, r, u, s);
  return s;
}

double residualFromVelocity(const std::vector<ConstraintBlock>& blocks, const Eigen::VectorXd& r,
                            const Eigen::VectorXd& u) {
  return std::sqrt(residualSquares(blocks, 0, static_cast<int>(blocks.size()), 0, r, u));
}

double residualSquares(const std::vector<ConstraintBlock>& blocks, int first, int last, int offset,
                       const Eigen::VectorXd& r, const Eigen::VectorXd& u) {
  double s = 0;
  for (int k = first; k < last; ++k) {
    accumulateBlockResidual(blocks[k], r.data() + offset, u.data() + offset, s);
    offset += blocks[k].size();
  }
  return s;
}

ResidualValue commonResidual(const ContactProblem& problem, const Eigen::VectorXd& r,
                             Eigen::VectorXd& u) {
  problem.W.velocity(r, problem.q, u);
  ResidualValue v;
  v.absolute = residualFromVelocity(problem.blocks, r, u);
  v.relative = v.absolute / (1.0 + plainNorm(problem.q));
  return v;
}

ResidualValue commonResidual(const ContactProblem& problem, const Eigen::VectorXd& r) {
  Eigen::VectorXd u;
  return commonResidual(problem, r, u);
}

}  // namespace coulomb::solvers
