#include <coulomb/geometry/Quaternion.hpp>

#include <cmath>

namespace coulomb::geometry {

Eigen::Quaterniond quaternionExp(const Eigen::Vector3d& rotationVector) {
  const double angle = rotationVector.norm();
  const double half = 0.5 * angle;
  // sin(half)/angle; below 1e-4 rad the series 1/2 - angle^2/48 is exact to double precision.
  const double scale = angle < 1e-4 ? 0.5 - angle * angle / 48.0 : std::sin(half) / angle;
  Eigen::Quaterniond q(std::cos(half), scale * rotationVector.x(), scale * rotationVector.y(),
                       scale * rotationVector.z());
  return q.normalized();
}

Eigen::Vector3d quaternionLog(const Eigen::Quaterniond& qIn) {
  Eigen::Quaterniond q = qIn.normalized();
  if (q.w() < 0.0) q.coeffs() = -q.coeffs();  // short arc: q and -q are the same rotation
  const double sinHalf = q.vec().norm();
  if (sinHalf < 1e-12) return 2.0 * q.vec();  // angle ~ 2 sin(half)
  const double angle = 2.0 * std::atan2(sinHalf, q.w());
  return (angle / sinHalf) * q.vec();
}

Eigen::Quaterniond integrateWorldRotation(const Eigen::Quaterniond& q,
                                          const Eigen::Vector3d& omegaWorld, double h) {
  return (quaternionExp(h * omegaWorld) * q).normalized();
}

Eigen::Quaterniond integrateBodyRotation(const Eigen::Quaterniond& q,
                                         const Eigen::Vector3d& omegaBody, double h) {
  return (q * quaternionExp(h * omegaBody)).normalized();
}

Eigen::Quaterniond axisRotation(int axis, double angle) {
  const double half = 0.5 * angle;
  Eigen::Quaterniond q(std::cos(half), 0.0, 0.0, 0.0);
  q.vec()[axis] = std::sin(half);
  return q;
}

}  // namespace coulomb::geometry
