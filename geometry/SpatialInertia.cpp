#include <coulomb/geometry/SpatialInertia.hpp>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <sstream>

namespace coulomb::geometry {

Eigen::Matrix3d SpatialInertia::inertiaAboutOrigin() const {
  const Eigen::Matrix3d c = skew(centerOfMass);
  return inertiaAboutCom + mass * c * c.transpose();
}

Matrix6d SpatialInertia::matrix() const {
  const Eigen::Matrix3d c = skew(centerOfMass);
  Matrix6d m;
  m.topLeftCorner<3, 3>() = inertiaAboutOrigin();
  m.topRightCorner<3, 3>() = mass * c;
  m.bottomLeftCorner<3, 3>() = mass * c.transpose();
  m.bottomRightCorner<3, 3>() = mass * Eigen::Matrix3d::Identity();
  return m;
}

SpatialInertia SpatialInertia::transformed(const Pose& pose) const {
  const Eigen::Matrix3d r = pose.rotationMatrix();
  return {mass, pose.apply(centerOfMass), r * inertiaAboutCom * r.transpose()};
}

SpatialInertia SpatialInertia::operator+(const SpatialInertia& other) const {
  const double total = mass + other.mass;
  if (total <= 0.0) return {};
  const Eigen::Vector3d com = (mass * centerOfMass + other.mass * other.centerOfMass) / total;
  // Parallel-axis theorem: each part's inertia moved from its own COM to the combined COM.
  const Eigen::Matrix3d a = skew(centerOfMass - com), b = skew(other.centerOfMass - com);
  const Eigen::Matrix3d inertia = inertiaAboutCom + mass * a * a.transpose() +
                                  other.inertiaAboutCom + other.mass * b * b.transpose();
  return {total, com, inertia};
}

PrincipalAxes principalAxes(const Eigen::Matrix3d& inertia) {
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(0.5 *
                                                              (inertia + inertia.transpose()));
  Eigen::Matrix3d axes = solver.eigenvectors();
  if (axes.determinant() < 0.0) axes.col(2) = -axes.col(2);  // keep a proper rotation
  PrincipalAxes result;
  result.moments = solver.eigenvalues();
  result.rotation = Eigen::Quaterniond(axes).normalized();
  return result;
}

std::optional<std::string> checkPhysicalValidity(double mass, const Eigen::Matrix3d& inertia) {
  std::ostringstream out;
  if (!std::isfinite(mass) || mass <= 0.0) {
    out << "mass must be finite and > 0 (got " << mass << ")";
    return out.str();
  }
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      if (!std::isfinite(inertia(i, j))) {
        out << "inertia[" << i << "][" << j << "] is not finite (got " << inertia(i, j) << ")";
        return out.str();
      }
  const double scale = inertia.cwiseAbs().maxCoeff();
  const double tolerance = 1e-9 * std::max(scale, 1e-300);
  for (int i = 0; i < 3; ++i)
    for (int j = i + 1; j < 3; ++j)
      if (std::abs(inertia(i, j) - inertia(j, i)) > tolerance) {
        out << "inertia is not symmetric: inertia[" << i << "][" << j << "] = " << inertia(i, j)
            << " but inertia[" << j << "][" << i << "] = " << inertia(j, i);
        return out.str();
      }
  const Eigen::Vector3d moments = principalAxes(inertia).moments;  // ascending
  if (moments[0] <= tolerance) {
    out << "inertia is not positive definite: smallest principal moment is " << moments[0]
        << " kg m^2 (moments " << moments.transpose() << ")";
    return out.str();
  }
  // Ascending order: only I0 + I1 >= I2 can fail.
  if (moments[0] + moments[1] < moments[2] - tolerance) {
    out << "inertia breaks the triangle inequality: principal moments " << moments[0] << " + "
        << moments[1] << " < " << moments[2] << " kg m^2 (no mass distribution has them)";
    return out.str();
  }
  return std::nullopt;
}

std::optional<std::string> checkPhysicalValidity(const SpatialInertia& inertia) {
  if (!inertia.centerOfMass.allFinite()) return "center_of_mass is not finite";
  return checkPhysicalValidity(inertia.mass, inertia.inertiaAboutCom);
}

}  // namespace coulomb::geometry
