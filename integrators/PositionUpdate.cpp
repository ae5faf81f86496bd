#include <coulomb/geometry/Quaternion.hpp>
#include <coulomb/integrators/FreeRotation.hpp>
#include <coulomb/integrators/PositionUpdate.hpp>

namespace coulomb::integrators {

void integratePositions(geometry::BodyState& state, double h) {
  integratePositions(state, h, 0, state.size());
}

void integratePositions(geometry::BodyState& state, double h, std::size_t first, std::size_t last) {
  using geometry::MotionType;
  for (std::size_t i = first; i < last; ++i) {
    if (state.alive[i] == 0 || state.motionTypes[i] == MotionType::Static || state.asleep[i] != 0)
      continue;
    geometry::Pose& pose = state.poses[i];
    pose.position += h * state.linearVelocities[i];
    if (state.motionTypes[i] == MotionType::Kinematic) {
      pose.rotation =
          geometry::integrateWorldRotation(pose.rotation, state.angularVelocities[i], h);
      continue;
    }
    const Eigen::Vector3d& moments = state.principalMoments[i];
    if (moments[0] > 0.0 && moments[0] == moments[1] && moments[1] == moments[2]) {
      // Three equal moments (spheres, cubes): L = I w, so the torque-free flow keeps w and turns
      // the body about it, and the world inertia I 1 does not depend on the orientation. One
      // rotation is the exact flow (the general path gives the same to round-off, at 3x the cost).
      const Eigen::Vector3d& w = state.angularVelocities[i];
      if (w[0] != 0.0 || w[1] != 0.0 || w[2] != 0.0)  // w = 0 (a ball that slides): no turn
        pose.rotation = geometry::integrateWorldRotation(pose.rotation, w, h);
      continue;
    }
    Eigen::Vector3d momentum;
    pose.rotation = torqueFreeOrientation(state, i, h, &momentum);
    state.refreshWorldInertia(i);
    state.angularVelocities[i] = state.worldInverseInertias[i] * momentum;
  }
}

}  // namespace coulomb::integrators
