#pragma once
// Torque-free rotation of a rigid body over one step by the symmetric splitting of
// Dullweber, Leimkuhler and McLachlan, "Symplectic splitting methods for rigid body molecular
// dynamics", J. Chem. Phys. 107(15), 1997, section III (the "rotation" splitting): the kinetic
// energy T = sum_k pi_k^2 / (2 I_k) is split per principal axis; each piece is an exact rotation
// about that axis by h pi_k / I_k, composed as 1(h/2) 2(h/2) 3(h) 2(h/2) 1(h/2).
// Properties: second order, symplectic, time-reversible; the world angular momentum is conserved
// exactly (each sub-rotation moves orientation and body momentum together) and |pi| is preserved.
// A step turns no axis by more than 1 rad: a faster spinner is sub-stepped, since at radians
// per step the splitting error pumps energy into the axis of the smallest moment.
// Bodies with two equal principal moments (symmetric tops: capsules, cylinders, cubes, spheres)
// take the exact flow instead, a regular precession (FreeRotation.cpp): two rotations, exact at
// any step; the splitting is for bodies with three different moments.
#include <coulomb/geometry/BodyState.hpp>

#include <Eigen/Geometry>

#include <cstddef>

namespace coulomb::integrators {

/// New orientation of a body after a torque-free step h with constant world angular momentum
/// `angularMomentum` [kg m^2/s]. `orientation` maps body to world, `principalFrame` maps principal
/// axes to body axes, `principalMoments` [kg m^2] are positive.
Eigen::Quaterniond rotateTorqueFree(const Eigen::Quaterniond& orientation,
                                    const Eigen::Quaterniond& principalFrame,
                                    const Eigen::Vector3d& principalMoments,
                                    const Eigen::Vector3d& angularMomentum, double h);

/// The flow itself on the principal frame Q (principal axes -> world) with the body momentum
/// pi = Q^T L: the new Q, not normalized.
Eigen::Quaterniond rotatePrincipalFrame(const Eigen::Quaterniond& toPrincipal,
                                        const Eigen::Vector3d& bodyMomentum,
                                        const Eigen::Vector3d& principalMoments, double h);

/// Dynamic body i's orientation after a torque-free step h with its current angular velocity:
/// what integratePositions produces and the predicted-state correction predicts (one function,
/// so the two agree to the bit). `momentum`, if given, receives its world angular momentum.
Eigen::Quaterniond torqueFreeOrientation(const geometry::BodyState& state, std::size_t i, double h,
                                         Eigen::Vector3d* momentum = nullptr);

}  // namespace coulomb::integrators
