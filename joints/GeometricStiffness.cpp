#include <coulomb/joints/GeometricStiffness.hpp>

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>

namespace coulomb::joints {

Eigen::Matrix3d rotationalGeometricStiffness(const Eigen::Vector3d& force,
                                             const Eigen::Vector3d& arm) {
  return arm * force.transpose() - force.dot(arm) * Eigen::Matrix3d::Identity();
}

Eigen::Matrix3d stabilizingInertia(const Eigen::Matrix3d& inertia, const Eigen::Matrix3d& stiffness,
                                   double h) {
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(0.5 *
                                                             (stiffness + stiffness.transpose()));
  Eigen::Matrix3d out = inertia;
  for (int j = 0; j < 3; ++j) {
    const Eigen::Vector3d v = eigen.eigenvectors().col(j);
    const double stiff = h * h * std::abs(eigen.eigenvalues()(j));  // (omega_j h)^2 I_j
    const double current = v.dot(inertia * v);
    // Beyond the explicit limit omega h = 2, raise I_j to omega h = sqrt(2). Not below it: an
    // inertia raised on every tensioned link (limit omega h = 1) gave the 10-link chain at
    // h = 0.01 +50 % energy instead of -50 % (docs/tuning.md).
    if (stiff > 4.0 * current) out += (0.5 * stiff - current) * v * v.transpose();
  }
  return out;
}

}  // namespace coulomb::joints
