#pragma once
// The joints' rows as one linear system over a PredictedStateWorkspace, shared by the
// predicted-state correction and the symmetric step's velocity projection (internal to
// integrators/): the rows at the bodies' poses and the structure of their coupling, the blocks of
// B = J_rows M^-1 J^T, its LU (the correction's Newton passes) or LDL^T (projections), and the
// impulses put on the bodies.
#include <coulomb/integrators/PredictedStateCorrection.hpp>

#include <span>
#include <vector>

namespace coulomb::integrators::joint_rows {

using Workspace = PredictedStateWorkspace;
using Matrix6k = Eigen::Matrix<double, 6, Eigen::Dynamic, 0, 6, 6>;
using Block3 = Eigen::Matrix<double, 3, 3, Eigen::RowMajor>;  // a block of B, 3-row joints
using Rows3 = Eigen::Matrix<double, 3, 6, Eigen::RowMajor>;   // a ball joint's side of J

bool dynamicBody(const geometry::BodyState& state, const geometry::BodyId& id);
/// The rows of `at` on touch t's side of its joint.
const joints::RowJacobian& side(const std::vector<joints::ConstraintEval>& at,
                                const Workspace::Touch& t);
/// v += M^-1 J^T p on every touched body, J the rows of `along`.
void applyRowImpulses(geometry::BodyState& state, const std::vector<joints::ConstraintEval>& along,
                      const Eigen::VectorXd& p, const Workspace& w);
/// w.minvJt = M^-1 J^T per touch, J the rows of `impulsesAt`.
void inverseMassTimesRows(const geometry::BodyState& state,
                          const std::vector<joints::ConstraintEval>& impulsesAt, Workspace& w);
/// w.b = blocks of J_rows M^-1 J^T (the rows' Jacobians taken from `rowsAt`, M^-1 J^T from
/// w.minvJt), plus `compliance` on every diagonal entry.
void assemble(const std::vector<joints::ConstraintEval>& rowsAt, double compliance, Workspace& w);
/// p = B^-1 w.target, B (w.b as assembled: B(a, b) and B(b, a) separate blocks) by LU; false when
/// the factorization fails (a singular pivot).
bool solveNewton(Workspace& w, Eigen::VectorXd& p);
/// p = (J M^-1 J^T)^-1 w.target (w.b assembled with the same rows twice) by LDL^T; false when the
/// factorization fails.
bool solveSymmetric(Workspace& w, Eigen::VectorXd& p);
/// w.start, w.offset and w.minvJt for the joints at the bodies' current poses, the structure
/// rebuilt when it changed; returns the compliance of every row, 1e-10 of the largest diagonal
/// entry of J M^-1 J^T (0 when no joint touches a dynamic body).
double rowsAtCurrentPoses(const geometry::BodyState& state,
                          std::span<const joints::JointDef* const> joints, Workspace& w);
/// `result` reset (no pass, zero impulses per joint, `converged` as given) and the joints' rows at
/// the bodies' current poses (rowsAtCurrentPoses); returns their compliance, 0 when there is
/// nothing to do (no joint, or none on a dynamic body).
double resetAtCurrentPoses(const geometry::BodyState& state,
                           std::span<const joints::JointDef* const> joints, Workspace& w,
                           PredictedStateResult& result, bool converged);

}  // namespace coulomb::integrators::joint_rows
