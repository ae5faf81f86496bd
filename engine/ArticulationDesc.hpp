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

struct ArticulationDesc {
  std::string name;                         // prefix of the link proxies' names ("name/link")
  std::vector<ArticulationLinkDesc> links;  // parent-first
  std::optional<Eigen::VectorXd> q;         // nq values; nullopt = neutral configuration
  std::optional<Eigen::VectorXd> qd;        // nv values; nullopt = at rest
  /// Contacts between links of this tree (adjacent links always excluded). Off by default.
  bool selfCollision = false;
  std::vector<LoopClosureDesc> loopClosures;
  /// Fraction of a loop-closure or joint-limit position error removed per step (Baumgarte).
  double errorReduction = 0.2;
};

}  // namespace coulomb::engine
