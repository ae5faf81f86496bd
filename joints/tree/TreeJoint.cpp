#include <coulomb/joints/tree/TreeJoint.hpp>

#include <cmath>
#include <sstream>
#include <stdexcept>
#include <utility>

namespace coulomb::joints::tree {

namespace {
TreeJoint make(TreeJointType type, std::string name, const geometry::Pose& parentToJoint,
               const Eigen::Vector3d& axis) {
  TreeJoint joint;
  joint.type = type;
  joint.name = std::move(name);
  joint.parentToJoint = parentToJoint;
  joint.axis = axis;
  return joint;
}

[[noreturn]] void fail(const TreeJoint& joint, const std::string& what) {
  std::ostringstream out;
  out << "tree joint '" << joint.name << "' (" << toString(joint.type) << "): " << what;
  throw std::invalid_argument(out.str());
}

Eigen::Quaterniond quaternionAt(const double* wxyz) {
  return Eigen::Quaterniond(wxyz[0], wxyz[1], wxyz[2], wxyz[3]).normalized();
}
}  // namespace

const char* toString(TreeJointType type) {
  switch (type) {
    case TreeJointType::Revolute:
      return "revolute";
    case TreeJointType::Continuous:
      return "continuous";
    case TreeJointType::Prismatic:
      return "prismatic";
    case TreeJointType::Fixed:
      return "fixed";
    case TreeJointType::Spherical:
      return "spherical";
    case TreeJointType::Floating:
      return "floating";
  }
  return "unknown";
}

TreeJoint TreeJoint::revolute(std::string name, const geometry::Pose& parentToJoint,
                              const Eigen::Vector3d& axis) {
  return make(TreeJointType::Revolute, std::move(name), parentToJoint, axis);
}
TreeJoint TreeJoint::continuous(std::string name, const geometry::Pose& parentToJoint,
                                const Eigen::Vector3d& axis) {
  return make(TreeJointType::Continuous, std::move(name), parentToJoint, axis);
}
TreeJoint TreeJoint::prismatic(std::string name, const geometry::Pose& parentToJoint,
                               const Eigen::Vector3d& axis) {
  return make(TreeJointType::Prismatic, std::move(name), parentToJoint, axis);
}
TreeJoint TreeJoint::fixed(std::string name, const geometry::Pose& parentToJoint) {
  return make(TreeJointType::Fixed, std::move(name), parentToJoint, Eigen::Vector3d::UnitZ());
}
TreeJoint TreeJoint::spherical(std::string name, const geometry::Pose& parentToJoint) {
  return make(TreeJointType::Spherical, std::move(name), parentToJoint, Eigen::Vector3d::UnitZ());
}
TreeJoint TreeJoint::floating(std::string name, const geometry::Pose& parentToJoint) {
  return make(TreeJointType::Floating, std::move(name), parentToJoint, Eigen::Vector3d::UnitZ());
}

int TreeJoint::nq() const {
  switch (type) {
    case TreeJointType::Revolute:
    case TreeJointType::Continuous:
    case TreeJointType::Prismatic:
      return 1;
    case TreeJointType::Fixed:
      return 0;
    case TreeJointType::Spherical:
      return 4;
    case TreeJointType::Floating:
      return 7;
  }
  return 0;
}

int TreeJoint::nv() const {
  switch (type) {
    case TreeJointType::Revolute:
    case TreeJointType::Continuous:
    case TreeJointType::Prismatic:
      return 1;
    case TreeJointType::Fixed:
      return 0;
    case TreeJointType::Spherical:
      return 3;
    case TreeJointType::Floating:
      return 6;
  }
  return 0;
}

Eigen::VectorXd TreeJoint::neutralConfiguration() const {
  Eigen::VectorXd q = Eigen::VectorXd::Zero(nq());
  if (type == TreeJointType::Spherical) q(0) = 1.0;
  if (type == TreeJointType::Floating) q(3) = 1.0;
  return q;
}

geometry::Pose TreeJoint::jointMotion(const double* q) const {
  switch (type) {
    case TreeJointType::Revolute:
    case TreeJointType::Continuous:
      return {Eigen::Quaterniond(Eigen::AngleAxisd(q[0], axis)), Eigen::Vector3d::Zero()};
    case TreeJointType::Prismatic:
      return geometry::Pose::translation(q[0] * axis);
    case TreeJointType::Fixed:
      return geometry::Pose::identity();
    case TreeJointType::Spherical:
      return {quaternionAt(q), Eigen::Vector3d::Zero()};
    case TreeJointType::Floating:
      return {quaternionAt(q + 3), Eigen::Vector3d(q[0], q[1], q[2])};
  }
  return geometry::Pose::identity();
}

MotionSubspace TreeJoint::motionSubspace() const {
  MotionSubspace s = MotionSubspace::Zero(6, nv());
  switch (type) {
    case TreeJointType::Revolute:
    case TreeJointType::Continuous:
      s.col(0).head<3>() = axis;
      break;
    case TreeJointType::Prismatic:
      s.col(0).tail<3>() = axis;
      break;
    case TreeJointType::Fixed:
      break;
    case TreeJointType::Spherical:
      s.topRows<3>().setIdentity();
      break;
    case TreeJointType::Floating:
      s.setIdentity();
      break;
  }
  return s;
}

void TreeJoint::validate() const {
  if (!parentToJoint.allFinite()) fail(*this, "parentToJoint is not finite");
  if (std::abs(parentToJoint.rotation.norm() - 1.0) > 1e-9)
    fail(*this, "parentToJoint.rotation is not a unit quaternion");
  if (nv() == 1) {
    if (!axis.allFinite()) fail(*this, "axis is not finite");
    if (std::abs(axis.norm() - 1.0) > 1e-9) {
      std::ostringstream out;
      out << "axis must be a unit vector (|axis| = " << axis.norm()
          << "); normalise it when loading";
      fail(*this, out.str());
    }
  }
  if (!std::isfinite(damping) || damping < 0.0) fail(*this, "damping must be finite and >= 0");
  if (!std::isfinite(armature) || armature < 0.0) fail(*this, "armature must be finite and >= 0");
  if (std::isnan(lower) || std::isnan(upper) || lower > upper)
    fail(*this, "limits must satisfy lower <= upper");
}

}  // namespace coulomb::joints::tree
