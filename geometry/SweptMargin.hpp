#pragma once
// Velocity-swept speculative margins. A pair's margin is the fixed margin plus how far its two
// bodies can travel toward each other during the coming step, so a contact row exists (with a
// positive gap) before the bodies meet, however fast they approach: the speculative bias
// u_N >= -gap/h then lets them close the gap but not pass through (Catto, "Continuous
// Collision", GDC 2013, speculative contacts; Bullet's and Box2D's speculative margins).
#include <coulomb/geometry/Collider.hpp>
#include <coulomb/geometry/Pose.hpp>
#include <coulomb/geometry/Shape.hpp>

#include <Eigen/Core>

#include <span>
#include <vector>

namespace coulomb::geometry {

/// Body velocities over the coming step, indexed by BodyId.index (the predicted v* of the step).
/// Empty spans or h = 0 (the default): no sweep, the fixed margin alone.
struct SweepMotion {
  std::span<const Eigen::Vector3d> linearVelocities;   // [m/s] COM velocity, world
  std::span<const Eigen::Vector3d> angularVelocities;  // [rad/s] world
  double h = 0.0;                                      // [s] the step
};

/// Largest distance of a point of the shape from its own origin [m]; 0 for a plane (infinite:
/// its rotation is not swept, only its translation).
double boundingRadius(const Shape& shape);

/// How far the surface of the shape can move per radian of rotation about its own origin [m]:
/// boundingRadius, except for a sphere (0) and a capsule (its half length): a ball's rounding
/// radius turns onto itself.
double rotationReach(const Shape& shape);

/// Per collider, how far its surface can travel in the step [m]: factor * h * (|v| + |w| r),
/// r = |local offset| + rotationReach (body frame = COM frame).
/// A pair's margin is margin + sweep[a] + sweep[b] >= margin + factor * (relative travel): the
/// sum of speeds, not their difference, because either body may be stopped by another contact in
/// the same solve (the box under a falling box lands on the floor), and the other then keeps its
/// speed relative to it. Non-finite or unusable entries get 0.
void colliderSweeps(const std::vector<Collider>& colliders, const std::vector<char>& usable,
                    const SweepMotion& motion, double factor, std::vector<double>& out);

}  // namespace coulomb::geometry
