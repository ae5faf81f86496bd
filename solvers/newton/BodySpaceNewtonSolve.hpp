#pragma once
// The Newton step's linear system in body space (docs/solvers.md "The Newton step in body
// space"): J_s d = b with J_s = A (W + s I) + B and W = J M^-1 J^T known by its factors
// (BodySpaceDelassus). With D = B + s A (block diagonal, invertible for s > 0: a sticking block is
// s rho I) the Sherman-Morrison-Woodbury identity gives
//   J_s^-1 = D^-1 - D^-1 A J (I + M^-1 J^T D^-1 A J)^-1 M^-1 J^T D^-1,
// so one step factors K = I + M^-1 J^T E J (E = D^-1 A), of 6 x bodies rows, instead of the
// contact rows of J_s. An island with more contact rows than velocities (four points per face, a
// column of boxes: 120 rows on 60 velocities) has the smaller system in body space. Measured
// errors of the direction stay those of the contact-space LU (both eps cond; the residual of every
// solve is checked by the caller).
#include <coulomb/solvers/BodySpaceDelassus.hpp>
#include <coulomb/solvers/newton/NewtonLinearSolver.hpp>

#include <Eigen/Core>

#include <array>
#include <vector>

namespace coulomb::solvers {

class BodySpaceNewtonSolve {
 public:
  /// Factors J_s for the factors `W` (blocks at `offset`), the blocks' A and B, and the shift
  /// s > 0. False when some D_b = B_b + s A_b is singular or not finite (the caller then solves
  /// in contact space).
  bool factor(const BodySpaceDelassus& W, const std::vector<int>& offset,
              const std::vector<NewtonBlockJacobian>& jac, double shift);
  /// x = J_s^-1 b with the last factors (b and x: W.size() entries, x is resized once).
  void solve(const Eigen::VectorXd& b, Eigen::VectorXd& x);
  /// Flops of a factorization in body space and of the contact-space LU of `keptRows` rows (its
  /// leading term (2/3) n^3): the caller takes the cheaper. In body space: forming K for the
  /// blocks' A and B (nothing for an open contact, the cached couplings for a sticking one,
  /// E J and G E J otherwise) plus K's block LU (eliminationFlops).
  double bodySpaceCost(const BodySpaceDelassus& W, const std::vector<NewtonBlockJacobian>& jac,
                       double eliminationFlops) const;
  static double contactSpaceCost(int keptRows);
  /// Flops of K's block LU over W's body graph with the fill of elimination in the bodies'
  /// order: per pivot its 6 x 6 LU, the solves of its row's blocks and the Schur updates. Depends
  /// on W's partition alone (the caller keeps it for a run).
  double eliminationFlops(const BodySpaceDelassus& W);

 private:
  const BodySpaceDelassus* W_ = nullptr;
  const std::vector<int>* offset_ = nullptr;
  std::vector<Eigen::Matrix3d> dInverse_, e_;  // per block: D_b^-1 and E_b = D_b^-1 A_b
  bool blockLu(const BodySpaceDelassus& W);
  void blockSolve(Eigen::VectorXd& z) const;
  // K and its block LU in the leading m x m block of storage sized to the largest m met (no
  // allocation when an island keeps its size); which 6 x 6 blocks are nonzero (with fill), the
  // pivot blocks' LU, and the lists of one elimination step.
  Eigen::MatrixXd k_;
  std::vector<char> nonzero_;
  std::vector<Eigen::Matrix<double, 6, 6>> pivotLu_;  // the pivot blocks' P A = L U
  std::vector<std::array<int, 6>> pivotRows_;         // ... and their row transpositions
  std::vector<std::array<int, 6>> pivotOrder_;        // ... as one row order
  std::vector<std::array<double, 6>> pivotInverse_;   // ... and 1 / U_kk
  std::vector<int> below_, right_;
  std::vector<char> graph_;  // eliminationFlops' symbolic pattern
  int m_ = 0;
  Eigen::VectorXd y_, g_, jz_;
};

}  // namespace coulomb::solvers
