#pragma once
// Everything needed to create a body. Poses and velocities are in world coordinates; shapes are
// placed in the body's reference frame (`pose`). The World moves the body frame to the centre of
// mass (axes unchanged) and re-expresses the shapes' local poses accordingly.
#include <coulomb/geometry/BodyState.hpp>
#include <coulomb/geometry/Collider.hpp>
#include <coulomb/geometry/SpatialInertia.hpp>
#include <coulomb/solvers/SolvePolicy.hpp>

#include <optional>
#include <string>
#include <vector>

namespace coulomb::engine {

struct ShapeDesc {
  geometry::Shape shape;
  geometry::Pose localPose;  // shape frame in the body's reference frame
  geometry::Material material;
  geometry::CollisionFilter filter;
  /// A sensor reports overlaps (World::sensorEvents) and never pushes (Collider::sensor). Its
  /// volume still adds to the body's mass at the body's density; give the body an explicit
  /// `mass` where that matters.
  bool sensor = false;
  std::uint64_t userData = 0;  // the user's value, on the Collider (never read by the engine)
};

struct BodyDesc {
  std::string name;  // optional; used in messages and scene look-ups
  geometry::MotionType motionType = geometry::MotionType::Dynamic;
  geometry::Pose pose;                                        // reference frame in world
  Eigen::Vector3d linearVelocity = Eigen::Vector3d::Zero();   // [m/s] of the COM, world
  Eigen::Vector3d angularVelocity = Eigen::Vector3d::Zero();  // [rad/s] world
  std::vector<ShapeDesc> shapes;
  /// [kg/m^3] Mass from the shapes at this density; nullopt: WorldSettings::defaultDensity.
  std::optional<double> density;
  /// Explicit mass, COM (reference frame) and inertia about the COM (reference axes); overrides
  /// the density. Required for a dynamic body without finite shapes.
  std::optional<geometry::SpatialInertia> mass;
  /// Which solvers this body's island gets (nullopt = the world's WorldSettings::solve.choice).
  std::optional<solvers::SolverChoice> solver;
  /// Continuous collision (Jolt's MotionQuality::LinearCast, Bullet's CCD): for fast, thin or
  /// spinning bodies. Every step, each pair this body may touch gets its time of impact along
  /// the motion of the step, and the contact is made at the features that meet then
  /// (docs/collision.md, "Continuous collision"). Off: no cost. Fast translation alone is caught
  /// without it by the swept speculative margins.
  bool continuousCollision = false;
  std::uint64_t userData = 0;  // the user's value (World::userData); never read by the engine
};

}  // namespace coulomb::engine
