#pragma once
// A Plücker coordinate transform between two link frames, stored as (E, r) rather than as a
// 6 x 6 matrix (Featherstone 2008, sec. 2.8 and Table 2.5): frame B has rotation E^T and origin r
// in frame A. Motion vectors go A -> B with X = [E 0; -E[r]x E] (eq. 2.24); forces go B -> A with
// X^T (eq. 2.25, X* = X^-T).
#include <coulomb/geometry/Pose.hpp>
#include <coulomb/geometry/Spatial.hpp>

namespace coulomb::joints::tree {

struct PluckerTransform {
  Eigen::Matrix3d e = Eigen::Matrix3d::Identity();
  Eigen::Vector3d r = Eigen::Vector3d::Zero();

  /// The transform A -> B where `bInA` is the pose of frame B in frame A.
  static PluckerTransform fromPose(const geometry::Pose& bInA) {
    return {bInA.rotationMatrix().transpose(), bInA.position};
  }

  /// X m: motion vector [w; v] in A to B coordinates.
  [[nodiscard]] geometry::Vector6d applyMotion(const geometry::Vector6d& m) const {
    const Eigen::Vector3d w = m.head<3>();
    return geometry::motionVector(e * w, e * (m.tail<3>() - r.cross(w)));
  }
  /// X^T f: force [n; f] in B to A coordinates (Table 2.5: n_A = E^T n + r x E^T f).
  [[nodiscard]] geometry::Vector6d applyTransposeForce(const geometry::Vector6d& f) const {
    const Eigen::Vector3d force = e.transpose() * f.tail<3>();
    return geometry::motionVector(e.transpose() * f.head<3>() + r.cross(force), force);
  }
  /// X^T F for the columns of a 6 x k matrix of forces.
  template <typename Derived>
  [[nodiscard]] Eigen::Matrix<double, 6, Eigen::Dynamic, 0, 6, 6> applyTransposeForces(
      const Eigen::MatrixBase<Derived>& forces) const {
    Eigen::Matrix<double, 6, Eigen::Dynamic, 0, 6, 6> out(6, forces.cols());
    for (Eigen::Index k = 0; k < forces.cols(); ++k)
      out.col(k) = applyTransposeForce(forces.col(k));
    return out;
  }
  /// X^T I X: a spatial inertia (or articulated inertia) in B coordinates moved to A (eq. 2.66).
  /// Block form: rotate the blocks of I = [A B; B^T C] by E, then shift by r:
  /// X^T I X = [A' - B' rx + rx (B'^T - C' rx), B' + rx C'; B'^T - C' rx, C'] with A' = E^T A E...
  [[nodiscard]] geometry::Matrix6d transformInertiaToParent(const geometry::Matrix6d& i) const {
    const Eigen::Matrix3d et = e.transpose();
    const Eigen::Matrix3d a = et * i.topLeftCorner<3, 3>() * e;
    const Eigen::Matrix3d b = et * i.topRightCorner<3, 3>() * e;
    const Eigen::Matrix3d c = et * i.bottomRightCorner<3, 3>() * e;
    const Eigen::Matrix3d rx = geometry::skew(r);
    const Eigen::Matrix3d lower = b.transpose() - c * rx;  // B'^T - C' rx
    geometry::Matrix6d out;
    out.topLeftCorner<3, 3>() = a - b * rx + rx * lower;
    out.topRightCorner<3, 3>() = b + rx * c;
    out.bottomLeftCorner<3, 3>() = lower;
    out.bottomRightCorner<3, 3>() = c;
    return out;
  }
  /// Composition: (this A -> B) then (next B -> C) gives A -> C.
  [[nodiscard]] PluckerTransform then(const PluckerTransform& next) const {
    return {next.e * e, r + e.transpose() * next.r};
  }
  [[nodiscard]] geometry::Matrix6d matrix() const {
    return geometry::motionTransform(e.transpose(), r);
  }
};

}  // namespace coulomb::joints::tree
