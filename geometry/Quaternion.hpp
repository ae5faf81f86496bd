#pragma once
// Unit-quaternion orientation helpers: the exponential map of SO(3) written in quaternions and the
// orientation updates built on it. Eigen stores (x, y, z, w); q rotates body vectors into world.
#include <Eigen/Geometry>

namespace coulomb::geometry {

/// exp(phi/2) as a unit quaternion: rotation by |phi| about phi/|phi|. Exact for any angle; a
/// Taylor series near zero keeps it accurate and finite for tiny |phi| (Grassia 1998, sec. 3).
Eigen::Quaterniond quaternionExp(const Eigen::Vector3d& rotationVector);

/// Inverse of quaternionExp on the short arc: returns phi with |phi| <= pi.
Eigen::Vector3d quaternionLog(const Eigen::Quaterniond& q);

/// q(t + h) for a constant world-frame angular velocity: exp(h omega) * q.
Eigen::Quaterniond integrateWorldRotation(const Eigen::Quaterniond& q,
                                          const Eigen::Vector3d& omegaWorld, double h);

/// q(t + h) for a constant body-frame angular velocity: q * exp(h omega).
Eigen::Quaterniond integrateBodyRotation(const Eigen::Quaterniond& q,
                                         const Eigen::Vector3d& omegaBody, double h);

/// Rotation by `angle` about coordinate axis `axis` (0, 1, 2) as a unit quaternion.
Eigen::Quaterniond axisRotation(int axis, double angle);

}  // namespace coulomb::geometry
