#pragma once
// Joints of a kinematic tree in reduced (joint) coordinates, Featherstone, "Rigid Body Dynamics
// Algorithms" (2008), chapter 4 (joint models, Table 4.1).
//
// A link's frame is placed by  X_link = X_parentLink * parentToJoint * jointMotion(q):
// `parentToJoint` is the pose of the joint frame in the parent link's frame (the URDF <origin>;
// for a root link, the pose in the world), and jointMotion(q) moves the child link relative to
// the joint frame. Coordinates per joint type (nq position coordinates, nv velocity coordinates):
//   Revolute, Continuous  nq = nv = 1  angle [rad] about `axis` (unit, joint frame)
//   Prismatic             nq = nv = 1  displacement [m] along `axis`
//   Fixed                 nq = nv = 0
//   Spherical             nq = 4 (unit quaternion w, x, y, z: child orientation in the joint
//                         frame), nv = 3 (angular velocity of the child in the CHILD frame)
//   Floating              nq = 7 (position x, y, z of the child origin in the joint frame, then
//                         the quaternion w, x, y, z), nv = 6 (the child's body twist in the CHILD
//                         frame, angular first: omega, then the velocity of the child origin;
//                         the convention of DART's FreeJoint and of Featherstone's S = 1)
// With these choices the motion subspace S (chapter 4, eq. 4.6) is constant in the child frame,
// so the bias c_J = 0 for every joint type here.
#include <coulomb/geometry/Pose.hpp>
#include <coulomb/geometry/Spatial.hpp>

#include <Eigen/Core>

#include <cstdint>
#include <limits>
#include <string>

namespace coulomb::joints::tree {

enum class TreeJointType : std::uint8_t {
  Revolute,
  Continuous,
  Prismatic,
  Fixed,
  Spherical,
  Floating
};

const char* toString(TreeJointType type);

/// Motion subspace S (6 x nv, nv <= 6) in the child link frame, angular rows first.
using MotionSubspace = Eigen::Matrix<double, 6, Eigen::Dynamic, 0, 6, 6>;
/// Small per-joint matrices and vectors (at most 6 x 6): no heap allocation.
using JointMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 6, 6>;
using JointVector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 6, 1>;

struct TreeJoint {
  TreeJointType type = TreeJointType::Fixed;
  std::string name;                                         // for error messages
  geometry::Pose parentToJoint;                             // joint frame in the parent link frame
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();          // unit, joint frame (1-DOF joints only)
  double damping = 0.0;                                     // [N m s/rad or N s/m] per DOF, >= 0
  double armature = 0.0;                                    // [kg m^2 or kg] added to M's diagonal
  double lower = -std::numeric_limits<double>::infinity();  // limits, for rows (not enforced)
  double upper = std::numeric_limits<double>::infinity();

  static TreeJoint revolute(std::string name, const geometry::Pose& parentToJoint,
                            const Eigen::Vector3d& axis);
  static TreeJoint continuous(std::string name, const geometry::Pose& parentToJoint,
                              const Eigen::Vector3d& axis);
  static TreeJoint prismatic(std::string name, const geometry::Pose& parentToJoint,
                             const Eigen::Vector3d& axis);
  static TreeJoint fixed(std::string name, const geometry::Pose& parentToJoint);
  static TreeJoint spherical(std::string name, const geometry::Pose& parentToJoint);
  static TreeJoint floating(std::string name,
                            const geometry::Pose& parentToJoint = geometry::Pose::identity());

  [[nodiscard]] int nq() const;
  [[nodiscard]] int nv() const;
  /// The coordinates of the zero motion (angle 0, identity quaternion, zero position).
  [[nodiscard]] Eigen::VectorXd neutralConfiguration() const;
  /// Pose of the child link frame in the joint frame for coordinates q (nq values; quaternions
  /// are normalised here, so a slightly drifted q still gives a rigid motion).
  [[nodiscard]] geometry::Pose jointMotion(const double* q) const;
  /// S of Featherstone eq. 4.6 in the child frame (Table 4.1 rows: revolute [a; 0], prismatic
  /// [0; a], spherical [1; 0], free 1).
  [[nodiscard]] MotionSubspace motionSubspace() const;
  /// Throws std::invalid_argument naming the joint when the axis is not unit, a value is not
  /// finite, damping or armature is negative, or parentToJoint is not a rigid transform.
  void validate() const;
};

}  // namespace coulomb::joints::tree
