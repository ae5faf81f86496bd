#pragma once
// Everything needed to create an articulation (a kinematic tree in reduced coordinates, see
// docs/articulations.md) in a World: its links with their joints, inertias and shapes, the
// initial joint state and the loop-closing constraints. Fixed or floating base is the root
// joint's type: a `floating` root joint is a floating base, anything else is welded to the world
// at the root joint's `parentToJoint` pose.
#include <coulomb/engine/BodyDesc.hpp>
#include <coulomb/geometry/SpatialInertia.hpp>
#include <coulomb/joints/tree/TreeConstraints.hpp>
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

// Loop closures, motors and mimic couplings are the tree's constraint models (joints/tree):
// LoopClosureDesc, JointMotorDesc (with JointMotorMode) and JointCouplingDesc.
using joints::tree::JointCouplingDesc;
using joints::tree::JointMotorDesc;
using joints::tree::JointMotorMode;
using joints::tree::LoopClosureDesc;

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
  std::uint64_t userData = 0;  // the user's value (World::userData(id)); never read
};

}  // namespace coulomb::engine
