#include <coulomb/solvers/StartSweep.hpp>

#include <coulomb/solvers/bgs/LocalContactSolver.hpp>

#include <Eigen/Cholesky>

#include <cmath>

namespace coulomb::solvers {

bool sweepContacts(const PreparedProblem& problem, Eigen::VectorXd& r) {
  if (problem.bodySpace) return false;
  const BlockSparseMatrix& W = problem.W;
  for (int b = 0; b < problem.blockCount(); ++b) {
    if (!problem.blocks[b].isContact()) continue;
    const int o = problem.offset[b];
    // q~ = q_b + sum over j != b of W_bj r_j: the contact's problem with the others held.
    Eigen::Vector3d qt = problem.q.segment<3>(o);
    const double* diagonal = nullptr;
    for (int k = W.rowBegin(b); k < W.rowEnd(b); ++k) {
      const int j = W.blockColumn(k);
      if (j == b) {
        diagonal = W.blockValues(k);
        continue;
      }
      const int oj = problem.offset[j], sj = problem.sizes[j];
      const double* v = W.blockValues(k);
      for (int a = 0; a < 3; ++a)
        for (int c = 0; c < sj; ++c) qt[a] += v[a * sj + c] * r[oj + c];
    }
    if (diagonal == nullptr) continue;  // not a valid problem (validate() names it)
    const double mu = problem.blocks[b].mu;
    if (qt[0] >= 0.0) {  // take-off: r = 0 leaves u = q~ in the dual cone
      r.segment<3>(o).setZero();
      continue;
    }
    const Eigen::Matrix3d Wbb =
        Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(diagonal);
    // Sticking (u = 0) when that answer lies in the cone: the closed form of (4.1) without the
    // local solver's set-up (its LU and spectral radii), the common case of a resting island.
    const Eigen::Vector3d stick = -Wbb.ldlt().solve(qt);
    if (stick.allFinite() && stick[0] > 0.0 && std::hypot(stick[1], stick[2]) <= mu * stick[0]) {
      r.segment<3>(o) = stick;
      continue;
    }
    const Eigen::Vector3d incoming = r.segment<3>(o);
    r.segment<3>(o) = solveLocalContact(LocalContactData::from(Wbb), qt, mu, incoming).r;
  }
  return true;
}

}  // namespace coulomb::solvers
