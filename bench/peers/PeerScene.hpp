#pragma once
// One scene description shared by the peer adapters (issue 12 item 3): a plain list of bodies
// with one primitive shape each, explicit mass and principal inertia, one material, and ball
// joints. It is made from Coulomb's built-in scene (samples/scenes/*.json, written after
// docs/conformance.md part A), so every engine builds exactly the same scene from one source.
#include <coulomb/io/SceneLoader.hpp>

#include <Eigen/Geometry>

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace coulomb::peers {

struct PeerShape {
  enum class Kind { Plane, Box, Sphere, Capsule };
  Kind kind = Kind::Box;
  Eigen::Vector3d halfExtents = Eigen::Vector3d::Zero();  // box
  double radius = 0.0;                                    // sphere, capsule
  double halfLength = 0.0;                                // capsule: cylinder half length
  // Capsule axis in the body frame (unit; Coulomb's capsule lies along its shape-frame z).
  Eigen::Vector3d capsuleAxis = Eigen::Vector3d::UnitZ();
  // Plane (static bodies only), in world: the surface {x : planeNormal . x = planeOffset}.
  Eigen::Vector3d planeNormal = Eigen::Vector3d::UnitZ();
  double planeOffset = 0.0;
  bool collides = true;  // false: a collision filter with an empty mask (the chain's links)
};

struct PeerBody {
  std::string name;
  bool isStatic = false;
  Eigen::Vector3d position = Eigen::Vector3d::Zero();  // COM, world
  Eigen::Quaterniond rotation = Eigen::Quaterniond::Identity();
  Eigen::Vector3d linearVelocity = Eigen::Vector3d::Zero();
  Eigen::Vector3d angularVelocity = Eigen::Vector3d::Zero();
  double mass = 0.0;                                  // 0 for static bodies
  Eigen::Vector3d inertia = Eigen::Vector3d::Zero();  // principal moments, body axes
  PeerShape shape;
  double friction = 0.0;
  double restitution = 0.0;
};

/// Ball joint; an index of -1 is the world (its anchor is then a world point).
struct PeerJoint {
  int bodyA = -1;
  int bodyB = -1;
  Eigen::Vector3d anchorA = Eigen::Vector3d::Zero();  // in A's COM frame
  Eigen::Vector3d anchorB = Eigen::Vector3d::Zero();  // in B's COM frame
};

struct PeerScene {
  std::string name;
  Eigen::Vector3d gravity = Eigen::Vector3d::Zero();
  double dt = 0.01;
  std::size_t steps = 0;
  std::vector<PeerBody> bodies;
  std::vector<PeerJoint> joints;
  engine::io::Scene source;  // the Coulomb scene it was made from (Coulomb builds this one)
};

/// The built-in scene `name` as a PeerScene. Throws CoulombError naming the body or joint when
/// the scene uses something the peer adapters do not model (several shapes per body, a COM
/// offset, non-diagonal inertia, joints other than ball joints, ...).
PeerScene loadPeerScene(std::string_view name);

}  // namespace coulomb::peers
