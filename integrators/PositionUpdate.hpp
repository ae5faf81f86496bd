#pragma once
// Last stage of a step: positions and orientations from the final velocities v+ (after contact
// impulses). Translation: x += h v+ (semi-implicit Euler). Orientation: kinematic bodies use the
// exponential map q <- exp(h omega) q; dynamic bodies convert omega+ to the world angular momentum
// L+ = I_world omega+ and follow the torque-free rotation (FreeRotation.hpp) with L+ held
// constant, then omega is re-expressed at the new orientation: omega = I_world(q_new)^-1 L+.
// See docs/tuning.md for how this composes with velocity-level contact impulses.
#include <coulomb/geometry/BodyState.hpp>

namespace coulomb::integrators {

void integratePositions(geometry::BodyState& state, double h);
/// The same for the bodies [first, last) only: each body on its own, so ranges can run on
/// different threads (the World's, WorldSettings::threads) with the same results.
void integratePositions(geometry::BodyState& state, double h, std::size_t first, std::size_t last);

}  // namespace coulomb::integrators
