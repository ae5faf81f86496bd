#pragma once
// The constraint rows of a kinematic tree in reduced coordinates (docs/articulations.md): joint
// limits, motors, dry joint friction, mimic couplings and loop closures, each a RowBlock on the
// link proxies (the maximal-coordinate bodies that stand for the links in the step). The
// assembler turns a side on link l into the joint-space row J_side * twistJacobian(l); a coupling,
// which spans up to four links, has zero body Jacobians and its joint-space row is given by
// couplingJointRow. The blocks carry no sourceKey: identity is the caller's.
#include <coulomb/geometry/Ids.hpp>
#include <coulomb/geometry/Pose.hpp>
#include <coulomb/joints/RowBlock.hpp>
#include <coulomb/joints/tree/Articulation.hpp>
#include <coulomb/joints/tree/TreeConstraints.hpp>

#include <Eigen/Core>

#include <span>

namespace coulomb::joints::tree {

/// What the rows of one tree read at the start of the step.
struct TreeRowFrame {
  const Articulation& model;
  std::span<const geometry::BodyId> linkBodies;  // each link's proxy body
  std::span<const geometry::Pose> linkPoses;     // world poses of the link frames
  const Eigen::VectorXd& q;
  const Eigen::VectorXd& qd;
  double errorReduction = 0.2;  // Baumgarte fraction for closures, couplings, limits past a stop
};

/// u = sign * qd_link for link `link`'s 1-DOF joint, as the relative twist of the link and its
/// parent along the joint axis (Equality kind, zero bias: callers set kind, bias and bounds).
[[nodiscard]] RowBlock jointRateRow(const TreeRowFrame& tree, int link, double sign);

/// Limit of link `link`'s 1-DOF joint (lower: u = qd >= 0 side, upper: u = -qd): speculative
/// while apart (the joint may reach the stop exactly in this step), Baumgarte when past it.
[[nodiscard]] RowBlock limitRow(const TreeRowFrame& tree, int link, bool lower, double h,
                                double warmStart);

/// Bounded row qd = target velocity with |lambda| <= maxEffort h (JointMotorDesc).
[[nodiscard]] RowBlock motorRow(const TreeRowFrame& tree, const JointMotorDesc& motor, double h,
                                double warmStart);

/// Dry friction of a 1-DOF joint (the model of joints::JointDef::friction): bounded row qd = 0
/// with |lambda| <= friction h; it holds the joint while the load stays below `friction`.
[[nodiscard]] RowBlock frictionRow(const TreeRowFrame& tree, int link, double friction, double h,
                                   double warmStart);

/// Equality row qd_f - multiplier qd_l + errorReduction (q_f - multiplier q_l - offset) / h = 0:
/// zero body Jacobians on the follower (side A) and leader (side B) proxies, the bias carrying
/// the joint-space J v* (v* = qd now); its joint-space row is couplingJointRow.
[[nodiscard]] RowBlock couplingRow(const TreeRowFrame& tree, const JointCouplingDesc& coupling,
                                   double h, double warmStart);
[[nodiscard]] Eigen::RowVectorXd couplingJointRow(const Articulation& model,
                                                  const JointCouplingDesc& coupling);

/// The point rows of a loop closure (one per enabled world axis): u = e . (v_B(pB) - v_A(pA))
/// with Baumgarte on the gap. `proxyPositionA/B` are the proxies' positions (the reference
/// points of their twists; B unused for a world anchor). warmStart per world axis.
[[nodiscard]] RowBlock closureRow(const TreeRowFrame& tree, const LoopClosureDesc& closure,
                                  const Eigen::Vector3d& proxyPositionA,
                                  const Eigen::Vector3d& proxyPositionB, double h,
                                  const Eigen::Vector3d& warmStart);

}  // namespace coulomb::joints::tree
