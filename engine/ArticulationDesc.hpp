#pragma once
// Everything needed to create an articulation (a kinematic tree in reduced coordinates, see
// docs/articulations.md) in a World: its links with their joints, inertias and shapes, the
// initial joint state and the loop-closing constraints. Fixed or floating base is the root
// joint's type: a `floating` root joint is a floating base, anything else is welded to the world
// at the root joint's `parentToJoint` pose.
#include <coulomb/engine/BodyDesc.hpp>
#include <coulomb/geometry/SpatialInertia.hpp>
#include <coulomb/joints/tree/TreeJoint.hpp>

#include <array>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <vector>

namespace coulomb::engine {

struct ArticulationLinkDesc {
  std::string name;
  int parent = -1;  // index of the parent link (< this link's index); -1 = the world
  joints::tree::TreeJoint joint;
  /// Mass, COM and inertia about the COM in the link frame; nullopt: from the shapes at the
  /// density (WorldSettings::defaultDensity unless `density` is set).
  std::optional<geometry::SpatialInertia> inertia;
  std::optional<double> density;  // [kg/m^3]
  std::vector<ShapeDesc> shapes;  // placed in the link frame
  /// [N m or N] Dry friction of the 1-DOF joint (URDF <dynamics friction>): one bounded row
  /// qd = 0 with |lambda| <= jointFriction h, as joints::JointDef::friction. 0 = none; ignored
  /// while a motor drives the joint (the motor row already bounds its effort).
  double jointFriction = 0.0;
};

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
/// error with ArticulationDesc::errorReduction). Both links need a 1-DOF joint.
struct JointCouplingDesc {
  int follower = 0;
  int leader = 0;
  double multiplier = 1.0;
  double offset = 0.0;
};

/// A constant generalised force on the 1-DOF joint of link `link` [N m or N], applied every step
/// (on top of World::applyJointForces, which is cleared each step).
struct JointTorqueDesc {
  int link = 0;
  double torque = 0.0;
};

struct ArticulationDesc {
  std::string name;                         // prefix of the link proxies' names ("name/link")
  std::vector<ArticulationLinkDesc> links;  // parent-first
  std::optional<Eigen::VectorXd> q;         // nq values; nullopt = neutral configuration
  std::optional<Eigen::VectorXd> qd;        // nv values; nullopt = at rest
  /// Contacts between links of this tree (adjacent links always excluded). Off by default.
  bool selfCollision = false;
  std::vector<LoopClosureDesc> loopClosures;
  std::vector<JointMotorDesc> motors;
  std::vector<JointCouplingDesc> couplings;
  std::vector<JointTorqueDesc> jointTorques;
  /// Fraction of a loop-closure, coupling or joint-limit position error removed per step
  /// (Baumgarte).
  double errorReduction = 0.2;
};

}  // namespace coulomb::engine
