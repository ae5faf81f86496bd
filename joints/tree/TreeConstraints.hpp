#pragma once
// Constraints on a kinematic tree beyond its joints (docs/articulations.md): loop closures,
// joint motors and mimic couplings, as a scene or URDF describes them. Their rows are emitted by
// joints/tree/TreeRowBlocks.
#include <Eigen/Core>

#include <array>
#include <cstdint>
#include <limits>

namespace coulomb::joints::tree {

/// A ball joint closing a kinematic loop: the point `anchorA` of link `linkA` and the point
/// `anchorB` of link `linkB` (link frames; linkB -1 = a point fixed in the world, given in world
/// coordinates) are held together by three equality rows (velocity level, with a Baumgarte term
/// on the position error). Example: a four-bar as a three-link tree plus one closure.
struct LoopClosureDesc {
  int linkA = 0;
  Eigen::Vector3d anchorA = Eigen::Vector3d::Zero();
  int linkB = -1;
  Eigen::Vector3d anchorB = Eigen::Vector3d::Zero();
  /// Only these world-axis rows of the point constraint (x, y, z). A planar loop whose joints
  /// already keep it in a plane needs only the two in-plane rows (the third is redundant).
  std::array<bool, 3> axes = {true, true, true};
};

/// A motor on the 1-DOF joint (revolute, continuous, prismatic) of link `link`: one bounded row
/// in joint space, qd_link = target velocity, with |impulse| <= maxEffort * h. Position mode is an
/// implicit PD servo: target velocity = positionGain * (target - q) / h (clamped to
/// +-maxVelocity), so the error shrinks by the factor (1 - positionGain) per step while the
/// effort suffices. Velocity mode drives qd to `target`.
enum class JointMotorMode : std::uint8_t { Position, Velocity };
struct JointMotorDesc {
  int link = 0;
  JointMotorMode mode = JointMotorMode::Position;
  double target = 0.0;        // [rad or m] (Position), [rad/s or m/s] (Velocity)
  double maxEffort = 0.0;     // [N m or N], > 0
  double positionGain = 0.2;  // (0, 1]: fraction of the position error removed per step
  double maxVelocity = std::numeric_limits<double>::infinity();  // [rad/s or m/s], > 0
};

/// A mimic coupling (URDF <mimic>): q_follower = multiplier * q_leader + offset, one equality
/// row in joint space (qd_follower - multiplier * qd_leader = 0, Baumgarte on the position
/// error with the articulation's error reduction). Both links need a 1-DOF joint.
struct JointCouplingDesc {
  int follower = 0;
  int leader = 0;
  double multiplier = 1.0;
  double offset = 0.0;
};

}  // namespace coulomb::joints::tree
