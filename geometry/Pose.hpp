#pragma once
// A rigid transform in SE(3): x_parent = rotation * x_child + position. Rotation is a unit
// quaternion (Eigen's (w, x, y, z) storage), kept normalised by the integrators.
#include <Eigen/Geometry>

namespace coulomb::geometry {

struct Pose {
  Eigen::Quaterniond rotation = Eigen::Quaterniond::Identity();
  Eigen::Vector3d position = Eigen::Vector3d::Zero();

  static Pose identity() { return {}; }
  static Pose translation(const Eigen::Vector3d& p) { return {Eigen::Quaterniond::Identity(), p}; }

  [[nodiscard]] Eigen::Vector3d apply(const Eigen::Vector3d& x) const {
    return rotation * x + position;
  }
  [[nodiscard]] Eigen::Vector3d applyInverse(const Eigen::Vector3d& x) const {
    return rotation.conjugate() * (x - position);
  }
  [[nodiscard]] Pose inverse() const {
    const Eigen::Quaterniond inv = rotation.conjugate();
    return {inv, -(inv * position)};
  }
  /// (this * other) maps other's child frame into this parent frame.
  [[nodiscard]] Pose operator*(const Pose& other) const {
    return {rotation * other.rotation, rotation * other.position + position};
  }
  [[nodiscard]] Eigen::Matrix3d rotationMatrix() const { return rotation.toRotationMatrix(); }
  [[nodiscard]] bool allFinite() const {
    return rotation.coeffs().allFinite() && position.allFinite();
  }
};

}  // namespace coulomb::geometry
