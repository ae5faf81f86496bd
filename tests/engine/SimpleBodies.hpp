#pragma once
// The bodies the embedding-API tests build again and again: a static floor plane, a cube of
// half side h with an explicit mass, and a ball at the default density.
#include <coulomb/engine/World.hpp>

namespace coulomb::testing {

inline geometry::BodyId addFloor(engine::World& world, double mu = 0.5) {
  engine::BodyDesc floor;
  floor.name = "floor";
  floor.motionType = geometry::MotionType::Static;
  floor.shapes.push_back({geometry::Plane{}, {}, {mu, 0.0}, {}});
  return world.createBody(floor);
}

/// A cube of half side `half` and mass `mass` (I = m 8 h^2 / 12 on every axis).
inline geometry::BodyId addCube(engine::World& world, const Eigen::Vector3d& at, double half = 0.1,
                                double mass = 1.0, double mu = 0.5) {
  engine::BodyDesc box;
  box.name = "box";
  box.pose.position = at;
  box.shapes.push_back({geometry::Box{Eigen::Vector3d::Constant(half)}, {}, {mu, 0.0}, {}});
  box.mass = geometry::SpatialInertia{
      mass, Eigen::Vector3d::Zero(), Eigen::Matrix3d::Identity() * mass * 8.0 * half * half / 12.0};
  return world.createBody(box);
}

inline geometry::BodyId addBall(engine::World& world, const Eigen::Vector3d& at,
                                double radius = 0.1) {
  engine::BodyDesc ball;
  ball.name = "ball";
  ball.pose.position = at;
  ball.shapes.push_back({geometry::Sphere{radius}, {}, {0.5, 0.0}, {}});
  return world.createBody(ball);
}

}  // namespace coulomb::testing
