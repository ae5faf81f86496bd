#pragma once
// Redundant equality rows (a kinematic loop's joint rows): the combinations of equality rows
// that are dependent up to round-off and the joints' drift, found by a rank-revealing sparse
// LDL^T of their block W_EE, and q's component along them removed (docs/solver-derivations.md
// (10.3)). Along such a combination c the bodies can barely move (c' W c ~ 1e-9 against ~1e2 on
// a rope bridge's planar loop), so any demand q_c there asks for impulses |q_c| / (c' W c) that
// are 1e4-1e6 times the load and changes the bodies' velocities by O(1): no solver reaches such
// an answer (they stall at the floor |q_c| / (1 + ||q||)), and none should, since the demand comes
// from the loop's drift (the Baumgarte bias, and J v* through rows that are redundant in the
// exact mechanism). Removing it leaves the problem the mechanism can meet.
#include <coulomb/solvers/ContactProblem.hpp>
#include <coulomb/solvers/direct/SparseLdlt.hpp>

#include <Eigen/Core>
#include <vector>

namespace coulomb::solvers {

struct RedundantRowsWorkspace {  // kept between calls: the pattern's analysis and the storage
  SparseLdlt ldlt;
  std::vector<int> rowOfEquality, blockOfEquality, equalityOfBlock, rows, cols, dependent;
  std::vector<double> values;
  Eigen::MatrixXd nullVectors;
  Eigen::VectorXd demand, original, vector, along, product;
};

struct RedundantDemand {
  int combinations = 0;  // dependent combinations of equality rows found
  double removed = 0.0;  // ||q_E - q_E'||, the demand removed along them [m/s or rad/s]
};

// A combination of rows is dependent when its LDL^T pivot is at most this fraction of W_EE's
// largest diagonal entry: sqrt(machine epsilon), the usual numerical-rank threshold (relative to
// the matrix's scale, as the compliance of docs/solver-derivations.md section 10). On the rope
// bridge the redundant directions sit at 5e-14..2e-10 of that scale and the smallest independent
// one at 1e-4, so the rank found does not hang on the exact value.
inline constexpr double kDependentPivot = 1.4901161193847656e-08;

/// Finds the dependent combinations of `problem`'s equality rows and removes q's component along
/// them (the Euclidean projection of q_E onto their orthogonal complement). Other rows, W and
/// the warm start are unchanged. Problems with fewer than two equality rows are left alone.
RedundantDemand removeRedundantDemands(ContactProblem& problem, RedundantRowsWorkspace& work);

}  // namespace coulomb::solvers
