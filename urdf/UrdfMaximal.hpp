#pragma once
// The maximal-coordinate form of a URDF robot (docs/urdf.md, "Maximal coordinates"): one free
// rigid body per UrdfBody (fused links stay fused) and one joints::JointDef per moving joint,
// instead of a reduced-coordinate Articulation. revolute/continuous -> Hinge (limits kept),
// prismatic -> Prismatic, fixed -> Fixed (only when fixed joints are not fused), floating -> no
// joint (a free body); a fixed base makes the root body Static at its pose. Joint friction
// becomes JointDef::friction. The bodies start at the link poses of the initial q, at rest.
// Used for comparisons with the tree and for loops closed by extra joints between the bodies.
#include <coulomb/engine/BodyDesc.hpp>
#include <coulomb/engine/World.hpp>
#include <coulomb/joints/JointDef.hpp>
#include <coulomb/urdf/UrdfLoader.hpp>

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace coulomb::engine::io {

struct UrdfMaximalOptions {
  /// A free body needs mass and a physical inertia: lighter bodies get this mass [kg], tensors
  /// whose smallest principal moment is below minimumInertia [kg m^2] are raised to it, and
  /// tensors that break the triangle inequality (kept by the tree, docs/urdf.md "Inertia
  /// policy") have their two smaller moments raised (warnings). Massless links of a tree (frames,
  /// point masses) and such tensors are fine in reduced coordinates only.
  double minimumMass = 1e-3;
  double minimumInertia = 1e-6;
  /// Shapes of the robot's bodies get this collision category and a mask without it, so that
  /// its links (jointed or not) do not collide with each other (the tree's default).
  std::uint32_t linkCategory = 1u << 31;
};

/// A joint of the maximal form: ends are indices into UrdfMaximal::bodies (-1 = the world),
/// frames in the bodies' reference frames (World::createJoint's convention).
struct UrdfMaximalJoint {
  int bodyA = -1;
  int bodyB = -1;
  joints::JointDef def;
};

struct UrdfMaximal {
  std::vector<BodyDesc> bodies;  // UrdfModel::bodies order, named "<name>/<body>"
  std::vector<UrdfMaximalJoint> joints;
  std::vector<std::string> warnings;  // lifted masses and inertias, damping not carried
  /// Index in `joints` of each moving 1-DOF URDF joint, by name.
  std::map<std::string, int> jointIndex;
};

/// `q` (the tree's nq values, nullopt = neutral) places the bodies. Throws CoulombError naming the
/// joint for a joint type without a maximal form (spherical), or naming the robot for a bad q.
UrdfMaximal toMaximal(const UrdfModel& model, const std::string& name,
                      const std::optional<Eigen::VectorXd>& q = std::nullopt,
                      const UrdfMaximalOptions& options = {});

/// Creates the bodies, then the joints, in `world`: their ids. A CoulombError from the World
/// (it should not happen for a toMaximal result) leaves the bodies created so far.
struct UrdfMaximalIds {
  std::vector<geometry::BodyId> bodies;
  std::vector<geometry::JointId> joints;
};
UrdfMaximalIds createMaximal(World& world, const UrdfMaximal& robot);

}  // namespace coulomb::engine::io
