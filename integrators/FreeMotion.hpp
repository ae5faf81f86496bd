#pragma once
// First stage of a step: predict the free velocities v* from the external forces (semi-implicit,
// "symplectic", Euler; Bender, Erleben, Trinkle 2014, section 2, eq. 9: v* = v + h M^-1 f_ext).
// The gyroscopic term omega x I omega is NOT applied here: it is carried exactly by the torque-free
// rotation in integratePositions (FreeRotation.hpp), which keeps the world angular momentum.
#include <coulomb/geometry/BodyState.hpp>

namespace coulomb::integrators {

/// For every dynamic body: v* = v + h (g + F/m), omega* = omega + h I_world^-1 tau, where F and
/// tau are the accumulated forces and torques. Static and kinematic bodies are left untouched.
/// `h` [s] must be finite and > 0 (checked by the caller).
void predictFreeVelocities(geometry::BodyState& state, const Eigen::Vector3d& gravity, double h);
/// The same for the bodies [first, last) only: each body on its own, so ranges can run on
/// different threads (the World's, WorldSettings::threads) with the same results.
void predictFreeVelocities(geometry::BodyState& state, const Eigen::Vector3d& gravity, double h,
                           std::size_t first, std::size_t last);

}  // namespace coulomb::integrators
