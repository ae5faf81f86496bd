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
    Eigen::Vector3d momentum;
    pose.rotation = torqueFreeOrientation(state, i, h, &momentum);
    state.refreshWorldInertia(i);
    state.angularVelocities[i] = state.worldInverseInertias[i] * momentum;
  }
}

}  // namespace coulomb::integrators
