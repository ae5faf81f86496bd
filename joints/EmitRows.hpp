#pragma once
// The row blocks of one joint for one step: its equality block (with the Baumgarte bias when
// that is the joint's policy), then its limit and motor/friction blocks (JointLimitMotor).
// Joints of an island are emitted before its contacts (RowSet.hpp), in joint order.
#include <coulomb/geometry/Pose.hpp>
#include <coulomb/joints/JointDef.hpp>
#include <coulomb/joints/RowBlock.hpp>
#include <coulomb/joints/Stabilization.hpp>

#include <Eigen/Core>

#include <vector>

namespace coulomb::joints {

/// Where the bodies of a joint are and how fast they move (world: identity pose, zero twist).
struct JointBodies {
  geometry::Pose poseA;
  geometry::Pose poseB;
  Eigen::Matrix<double, 6, 1> twistA = Eigen::Matrix<double, 6, 1>::Zero();  // (v, omega) at v*
  Eigen::Matrix<double, 6, 1> twistB = Eigen::Matrix<double, 6, 1>::Zero();
};

/// Appends the joint's blocks to `out`; the first is always the equality block. `policy` is the
/// joint's effective stabilization. Baumgarte bias on equality row i (survey sec. 4.4.1):
///   b_i = beta sign(C_i) max(|C_i| - slop, 0) / h,  so that J v+ = -b drives C toward 0.
/// Limits always use beta of `policy.baumgarte` for their push-out. Returns the blocks appended.
int emitJointRows(const JointDef& def, const JointBodies& bodies, const Stabilization& policy,
                  double h, std::vector<RowBlock>& out);

}  // namespace coulomb::joints
