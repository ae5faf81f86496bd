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
  const Eigen::Matrix3d symmetric = 0.5 * (stiffness + stiffness.transpose());
  // Without an eigen-decomposition when no direction can need it: 16 I^2 - h^4 S^2 positive
  // definite gives h^2 |S| < 4 I (the square root is operator monotone), so h^2 |k_j| < 4 I_j for
  // every eigenpair. A link under tension T along its axis passes exactly when h^2 T L < 4 I.
  const double h2 = h * h;
  const Eigen::Matrix3d scaled = h2 * symmetric;
  Eigen::Matrix3d margin = 16.0 * (inertia * inertia) - scaled * scaled;
  margin = 0.5 * (margin + margin.transpose()).eval();
  const double minor2 = margin(0, 0) * margin(1, 1) - margin(0, 1) * margin(0, 1);
  if (margin(0, 0) > 0.0 && minor2 > 0.0 && margin.determinant() > 0.0) return inertia;
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(symmetric);
  Eigen::Matrix3d out = inertia;
  for (int j = 0; j < 3; ++j) {
    const Eigen::Vector3d v = eigen.eigenvectors().col(j);
    const double stiff = h2 * std::abs(eigen.eigenvalues()(j));  // (omega_j h)^2 I_j
    const double current = v.dot(inertia * v);
    // Beyond the explicit limit omega h = 2, raise I_j to omega h = sqrt(2). Not below it: an
    // inertia raised on every tensioned link (limit omega h = 1) gave the 10-link chain at
    // h = 0.01 +50 % energy instead of -50 % (docs/tuning.md).
    if (stiff > 4.0 * current) out += (0.5 * stiff - current) * v * v.transpose();
  }
  return out;
}

}  // namespace coulomb::joints
