#pragma once
// Small worlds built in code for the robustness tests (a ground plane, boxes, spheres).
#include <coulomb/engine/World.hpp>

#include <string>

namespace coulomb::robustness {

inline engine::BodyDesc ground() {
  engine::BodyDesc d;
  d.name = "ground";
  d.motionType = geometry::MotionType::Static;
  d.shapes.push_back({geometry::Plane{}, {}, {}, {}});
  return d;
}

inline engine::BodyDesc box(const std::string& name, const Eigen::Vector3d& position,
                            double halfExtent = 0.1, double density = 1000.0) {
  engine::BodyDesc d;
  d.name = name;
  d.pose.position = position;
  d.density = density;
  d.shapes.push_back({geometry::Box{Eigen::Vector3d::Constant(halfExtent)}, {}, {}, {}});
  return d;
}

inline engine::BodyDesc sphere(const std::string& name, const Eigen::Vector3d& position,
                               double radius = 0.1) {
  engine::BodyDesc d;
  d.name = name;
  d.pose.position = position;
  d.shapes.push_back({geometry::Sphere{radius}, {}, {}, {}});
  return d;
}

/// True if every live body's pose and velocities are finite (the "no NaN in the state" check).
inline bool stateIsFinite(const engine::World& world) {
  const geometry::BodyState& s = world.state();
  for (std::size_t i = 0; i < s.size(); ++i)
    if (!s.poses[i].allFinite() || !s.linearVelocities[i].allFinite() ||
        !s.angularVelocities[i].allFinite())
      return false;
  return true;
}

}  // namespace coulomb::robustness
