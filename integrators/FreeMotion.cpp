#include <coulomb/integrators/FreeMotion.hpp>

namespace coulomb::integrators {

void predictFreeVelocities(geometry::BodyState& state, const Eigen::Vector3d& gravity, double h) {
  predictFreeVelocities(state, gravity, h, 0, state.size());
}

void predictFreeVelocities(geometry::BodyState& state, const Eigen::Vector3d& gravity, double h,
                           std::size_t first, std::size_t last) {
  for (std::size_t i = first; i < last; ++i) {
    if (!state.isDynamic(i)) continue;
    state.linearVelocities[i] += h * (gravity + state.inverseMasses[i] * state.forces[i]);
    // A torque impulse h tau changes the world angular momentum by h tau; at fixed orientation
    // that is omega += I_world^-1 h tau.
    state.angularVelocities[i] += h * (state.worldInverseInertias[i] * state.torques[i]);
  }
}

}  // namespace coulomb::integrators
