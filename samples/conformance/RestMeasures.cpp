#include "RestMeasures.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <type_traits>
#include <variant>

namespace coulomb::conformance {

DisplacementTracker::DisplacementTracker(const engine::World& world) {
  for (const geometry::Pose& pose : world.state().poses) start_.push_back(pose.position);
}

double DisplacementTracker::sample(const engine::World& world) {
  double now = 0.0;
  for (std::size_t i = 0; i < world.state().size() && i < start_.size(); ++i)
    if (world.state().isDynamic(i)) now = std::max(now, displacement(world, i));
  max_ = std::max(max_, now);
  return now;
}

double DisplacementTracker::displacement(const engine::World& world, std::size_t index) const {
  return (world.state().poses[index].position - start_[index]).norm();
}

double kineticEnergy(const engine::World& world) {
  double energy = 0.0;
  for (std::size_t i = 0; i < world.state().size(); ++i)
    if (world.state().isDynamic(i)) energy += world.state().kineticEnergy(i);
  return energy;
}

namespace {

// Lowest z of one shape at world pose `pose` (support point in -z).
double lowestPoint(const geometry::Shape& shape, const geometry::Pose& pose) {
  const Eigen::Matrix3d r = pose.rotationMatrix();
  const double z = pose.position.z();
  return std::visit(
      [&](const auto& s) -> double {
        using T = std::decay_t<decltype(s)>;
        if constexpr (std::is_same_v<T, geometry::Sphere>) {
          return z - s.radius;
        } else if constexpr (std::is_same_v<T, geometry::Box>) {
          return z - r.row(2).cwiseAbs().dot(s.halfExtents);
        } else if constexpr (std::is_same_v<T, geometry::Capsule>) {
          return z - std::abs(r(2, 2)) * s.halfLength - s.radius;
        } else if constexpr (std::is_same_v<T, geometry::Cylinder>) {
          return z - std::abs(r(2, 2)) * s.halfLength - s.radius * std::hypot(r(2, 0), r(2, 1));
        } else if constexpr (std::is_same_v<T, geometry::Plane>) {
          return -std::numeric_limits<double>::infinity();
        } else {  // hull or mesh: the lowest vertex
          double lowest = std::numeric_limits<double>::infinity();
          for (const Eigen::Vector3d& v : s.vertices)
            lowest = std::min(lowest, z + r.row(2).dot(v));
          return lowest;
        }
      },
      shape);
}

}  // namespace

double lowestDynamicPoint(const engine::World& world) {
  const geometry::BodyState& state = world.state();
  double lowest = std::numeric_limits<double>::infinity();
  for (const geometry::Collider& collider : world.colliders()) {
    const std::size_t i = collider.body.index;
    if (!collider.shape || i >= state.size() || !state.isDynamic(i)) continue;
    lowest = std::min(lowest, lowestPoint(*collider.shape, state.poses[i] * collider.localPose));
  }
  return lowest;
}

bool stateFinite(const engine::World& world) {
  const geometry::BodyState& state = world.state();
  for (std::size_t i = 0; i < state.size(); ++i)
    if (!state.poses[i].allFinite() || !state.linearVelocities[i].allFinite() ||
        !state.angularVelocities[i].allFinite())
      return false;
  return true;
}

}  // namespace coulomb::conformance
