#pragma once
// Mass, centre of mass and rotational inertia of a rigid body, with the algebra needed to combine
// shapes (parallel-axis theorem) and a physical-validity check that names the wrong value.
#include <coulomb/geometry/Pose.hpp>
#include <coulomb/geometry/Spatial.hpp>

#include <optional>
#include <string>

namespace coulomb::geometry {

struct SpatialInertia {
  double mass = 0.0;                                          // [kg]
  Eigen::Vector3d centerOfMass = Eigen::Vector3d::Zero();     // [m] in the reference frame
  Eigen::Matrix3d inertiaAboutCom = Eigen::Matrix3d::Zero();  // [kg m^2] reference-frame axes

  /// Rotational inertia about the reference-frame origin (parallel-axis theorem).
  [[nodiscard]] Eigen::Matrix3d inertiaAboutOrigin() const;
  /// 6x6 spatial inertia about the reference origin, Featherstone (2008) eq. 2.63:
  /// [Ic + m [c]x[c]x^T, m [c]x; m [c]x^T, m 1].
  [[nodiscard]] Matrix6d matrix() const;
  /// The same body seen from a parent frame in which the reference frame sits at `pose`.
  [[nodiscard]] SpatialInertia transformed(const Pose& pose) const;
  /// Sum of two bodies rigidly joined (masses add, COM is the mass-weighted mean).
  [[nodiscard]] SpatialInertia operator+(const SpatialInertia& other) const;
};

/// Principal moments (ascending) and the rotation whose columns are the principal axes
/// (right-handed), for a symmetric inertia: inertia = R diag(moments) R^T.
struct PrincipalAxes {
  Eigen::Vector3d moments = Eigen::Vector3d::Zero();
  Eigen::Quaterniond rotation = Eigen::Quaterniond::Identity();
};
PrincipalAxes principalAxes(const Eigen::Matrix3d& inertia);

/// nullopt for a physically valid mass and inertia, else a message naming the first broken value:
/// non-finite or non-positive mass, non-finite entry inertia[i][j], asymmetry, a non-positive
/// principal moment (not positive definite), or principal moments breaking the triangle
/// inequality I_a + I_b >= I_c (every real mass distribution satisfies it).
std::optional<std::string> checkPhysicalValidity(double mass, const Eigen::Matrix3d& inertia);
std::optional<std::string> checkPhysicalValidity(const SpatialInertia& inertia);

}  // namespace coulomb::geometry
