#pragma once
// URDF robots (docs/urdf.md): a URDF file parsed by urdfdom (plus a pre-check of the XML that
// gives line numbers and actionable errors) becomes a plain, engine-independent UrdfModel: bodies
// after fusing fixed joints, their joints in reduced coordinates, inertias, collision shapes,
// mimic couplings and the warnings the file deserved. `toArticulation` turns it into a
// joints::tree::Articulation. Every error is a CoulombError
// "<file>:<line>: <element>: <problem>. <what to fix>".
#include <coulomb/engine/ArticulationDesc.hpp>
#include <coulomb/engine/CoulombError.hpp>
#include <coulomb/geometry/Collider.hpp>
#include <coulomb/geometry/Pose.hpp>
#include <coulomb/geometry/Shape.hpp>
#include <coulomb/geometry/SpatialInertia.hpp>
#include <coulomb/joints/tree/Articulation.hpp>

#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace coulomb::engine::io {

enum class UrdfBase {
  Fixed,    // the root link welded to the world at UrdfOptions::basePose (the default)
  Floating  // the root link free (6 DOF floating joint, TreeJoint.hpp's convention)
};

struct UrdfOptions {
  UrdfBase base = UrdfBase::Fixed;
  geometry::Pose basePose;  // pose of the root link in the world (ignored for a root `world`)
  /// Weld links joined by fixed joints into one body (mass properties combined). Off: every URDF
  /// link is a body and fixed joints are TreeJoint::fixed.
  bool fuseFixedJoints = true;
  /// Apply <dynamics damping> as TreeJoint::damping. Off: pure rigid-body dynamics (as DART's
  /// reference numbers and `coulomb urdf dynamics`).
  bool jointDamping = true;
  /// Load <collision> meshes through geometry::loadTriangleMesh (as convex hulls). Off: meshes are
  /// listed in UrdfBody::skippedMeshes but not read (fast, no files needed).
  bool loadCollisionMeshes = true;
  /// Extra folders searched for package:// and relative mesh paths, before the environment
  /// variable COULOMB_PACKAGE_PATH (':'-separated) and the URDF's own folder (docs/urdf.md).
  std::vector<std::filesystem::path> packagePath;
  /// Friction of a collider: <gazebo reference="link"><mu1> if the file has a valid one (value
  /// attribute or element text), else this map by the name of the link's visual <material>, else
  /// defaultFriction.
  std::map<std::string, double> materialFriction;
  double defaultFriction = 0.8;
  /// Inertia given to a body whose whole subtree behind a moving joint is massless (ABA would
  /// divide by zero): a small sphere-like inertia, with a warning.
  double masslessSubtreeMass = 1e-6;         // [kg]
  double masslessSubtreeInertia = 1e-10;     // [kg m^2] on each principal axis
  Eigen::Vector3d gravity{0.0, 0.0, -9.81};  // for toArticulation
};

struct UrdfCollision {
  geometry::Shape shape;
  geometry::Pose pose;          // shape frame in the body frame
  geometry::Material material;  // friction per the policy of UrdfOptions
  std::string link;             // URDF link that declared it (may be fused into the body)
  std::string description;      // "box 0.1 x 0.2 x 0.3", "mesh meshes/a.stl", ...
};

struct UrdfMimic {
  std::string joint;  // follower: q_joint = multiplier * q_leader + offset
  std::string leader;
  double multiplier = 1.0;
  double offset = 0.0;
};

/// What the loader did with a body's inertia (docs/urdf.md, "Inertia policy").
enum class UrdfInertiaStatus : std::uint8_t {
  Physical,   // mass > 0 and a tensor some rigid body has (geometry::checkPhysicalValidity)
  PointMass,  // mass > 0, zero tensor
  Massless,   // mass 0 (a frame, or mass 0 with a tensor: kept)
  AsWritten,  // semidefinite but no rigid body has it (triangle inequality broken, or singular):
              // kept as the file writes it, with a warning; a tree needs no more
  Repaired,   // not semidefinite, or a massless subtree behind a moving joint: changed (warning)
};
const char* toString(UrdfInertiaStatus status);  // "physical", "point_mass", ...

/// One rigid body of the tree: a URDF link plus every link welded to it by fixed joints.
struct UrdfBody {
  std::string name;  // the URDF link at the body's frame
  int parent = -1;   // body index, -1 = the world
  joints::tree::TreeJoint joint;
  geometry::SpatialInertia inertia;     // body frame; combined over the fused links
  std::vector<std::string> fusedLinks;  // other URDF links welded into this body
  std::vector<UrdfCollision> collisions;
  std::vector<std::string> skippedMeshes;  // meshes not loaded (UrdfOptions::loadCollisionMeshes)
  double jointFriction = 0.0;              // <dynamics friction> [N m or N]: joint friction rows
  double effortLimit = 0.0;                // <limit effort>, 0 = none given
  double velocityLimit = 0.0;              // <limit velocity>, 0 = none given
  bool inertiaValid = true;                // mass > 0 and physically valid (SpatialInertia.hpp)
  UrdfInertiaStatus inertiaStatus = UrdfInertiaStatus::Physical;
};

/// What the file's <gazebo> extensions gave (docs/urdf.md, "Gazebo extensions"). Coulomb uses
/// <mu1> of blocks that reference a link as that link's friction (and counts <mu2> as used when
/// it equals mu1); every other child, and every block of the whole robot or of a joint, is
/// ignored and counted here by element name. Invalid values are warnings, never errors.
struct UrdfGazeboUse {
  int blocks = 0;                          // <gazebo> elements in the file
  std::map<std::string, double> friction;  // link -> mu1: its colliders' friction
  std::map<std::string, int> used;         // element name -> count ("mu1", "mu2")
  std::map<std::string, int> ignored;      // element name -> count ("plugin", "kp", ...)
};

struct UrdfFrame {
  int body = -1;        // -1: the world (a root link named `world`)
  geometry::Pose pose;  // URDF link frame in the body frame
};

struct UrdfModel {
  std::string file;  // as given, for messages
  std::string robotName;
  int urdfLinkCount = 0, urdfJointCount = 0;
  std::vector<UrdfBody> bodies;             // parent-first (Articulation order)
  std::vector<std::string> dofNames;        // moving joints in velocity order
  std::map<std::string, UrdfFrame> frames;  // every URDF link
  std::vector<UrdfMimic> mimics;            // not yet enforced: the followers are free DOFs
  std::vector<std::string> warnings;        // what was repaired, dropped or ignored, and why
  UrdfGazeboUse gazebo;                     // <gazebo> extensions: used and ignored
  bool floatingBase = false;
  Eigen::Vector3d gravity{0.0, 0.0, -9.81};

  [[nodiscard]] double totalMass() const;
  [[nodiscard]] int dofCount() const { return static_cast<int>(dofNames.size()); }
};

/// Reads, checks and converts a URDF file. Mesh paths resolve against options.packagePath,
/// COULOMB_PACKAGE_PATH and the file's folder.
UrdfModel loadUrdfFile(const std::filesystem::path& file, const UrdfOptions& options = {});
/// The same from text; `source` names it in messages, `baseDirectory` stands for its folder.
UrdfModel parseUrdf(const std::string& text, const std::string& source,
                    const std::filesystem::path& baseDirectory, const UrdfOptions& options = {});

/// The reduced-coordinate tree (bodies in order, gravity of the model). Throws CoulombError if
/// the Articulation refuses the model (it should not for a model this loader produced).
joints::tree::Articulation toArticulation(const UrdfModel& model);

/// The model as a World articulation (World::createArticulation): links with their joints,
/// inertias (always explicit), collision shapes and joint friction (ArticulationLinkDesc::
/// jointFriction, friction rows); `name` prefixes the link proxies. The root
/// joint (weld or floating) is placed at UrdfOptions::basePose as loaded. Mimic couplings are not
/// carried (not enforced yet).
ArticulationDesc toArticulationDesc(const UrdfModel& model, const std::string& name);

}  // namespace coulomb::engine::io
