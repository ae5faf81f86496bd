#pragma once
// Spatial (6D) motion and force vectors, Featherstone, "Rigid Body Dynamics Algorithms" (2008),
// chapter 2. Plücker coordinates with the angular part first: motion m = [omega; v],
// force f = [n; f]. Kept light (inline, fixed-size Eigen): the articulated-body algorithm builds
// on it later.
#include <Eigen/Geometry>  // cross()

namespace coulomb::geometry {

using Vector6d = Eigen::Matrix<double, 6, 1>;
using Matrix6d = Eigen::Matrix<double, 6, 6>;

/// [a]x such that skew(a) * b == a.cross(b).
inline Eigen::Matrix3d skew(const Eigen::Vector3d& a) {
  Eigen::Matrix3d s;
  s << 0.0, -a.z(), a.y(), a.z(), 0.0, -a.x(), -a.y(), a.x(), 0.0;
  return s;
}

inline Vector6d motionVector(const Eigen::Vector3d& angular, const Eigen::Vector3d& linear) {
  Vector6d m;
  m << angular, linear;
  return m;
}

inline Eigen::Vector3d angularPart(const Vector6d& v) {
  return v.head<3>();
}
inline Eigen::Vector3d linearPart(const Vector6d& v) {
  return v.tail<3>();
}

/// Motion cross product m x n (Featherstone eq. 2.31):
/// [w; v] x [w'; v'] = [w x w'; w x v' + v x w'].
inline Vector6d crossMotion(const Vector6d& m, const Vector6d& n) {
  const Eigen::Vector3d w = m.head<3>(), v = m.tail<3>();
  return motionVector(w.cross(n.head<3>()), w.cross(n.tail<3>()) + v.cross(n.head<3>()));
}

/// Force cross product m x* f (Featherstone eq. 2.32):
/// [w; v] x* [n; f] = [w x n + v x f; w x f].
inline Vector6d crossForce(const Vector6d& m, const Vector6d& f) {
  const Eigen::Vector3d w = m.head<3>(), v = m.tail<3>();
  return motionVector(w.cross(f.head<3>()) + v.cross(f.tail<3>()), w.cross(f.tail<3>()));
}

/// The 6x6 matrix of m x (crm in Featherstone's notation, eq. 2.31); m x* is -crm(m)^T.
inline Matrix6d crossMotionMatrix(const Vector6d& m) {
  Matrix6d x = Matrix6d::Zero();
  x.topLeftCorner<3, 3>() = skew(m.head<3>());
  x.bottomLeftCorner<3, 3>() = skew(m.tail<3>());
  x.bottomRightCorner<3, 3>() = skew(m.head<3>());
  return x;
}

/// Plücker transform of motion vectors from frame A to frame B, where B is obtained from A by
/// rotation E (B's axes in A, transposed: E = R^T) and translation r (B's origin in A):
/// X = [E 0; -E [r]x  E] (Featherstone eq. 2.24).
inline Matrix6d motionTransform(const Eigen::Matrix3d& rotationBInA, const Eigen::Vector3d& r) {
  const Eigen::Matrix3d e = rotationBInA.transpose();
  Matrix6d x = Matrix6d::Zero();
  x.topLeftCorner<3, 3>() = e;
  x.bottomRightCorner<3, 3>() = e;
  x.bottomLeftCorner<3, 3>() = -e * skew(r);
  return x;
}

}  // namespace coulomb::geometry
