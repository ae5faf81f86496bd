#pragma once
// What a World user may change about the contacts of a step before they are solved (Jolt's
// ContactListener::OnContactAdded/Persisted settings, Box2D v3's pre-solve and custom filter):
// a pair filter that decides which collider pairs are detected at all, and a pre-solve hook
// that sees every contact manifold of the step and may change its friction, restitution and
// surface velocity, or turn it off for this step (docs/embedding.md, "Contact events and hooks").
#include <coulomb/geometry/Collider.hpp>
#include <coulomb/geometry/ContactManifold.hpp>

#include <Eigen/Core>

#include <functional>

namespace coulomb::engine {

/// One contact manifold of this step as the pre-solve hook sees it. The manifold (colliders,
/// bodies, normal from A to B, points with depths) is read-only; the four fields below start at
/// the pair's material values and are what the solve uses.
struct ContactModification {
  const geometry::ContactManifold& manifold;
  const geometry::Collider& colliderA;  // manifold.colliderA
  const geometry::Collider& colliderB;  // manifold.colliderB
  double friction;                      // [-] >= 0, finite
  double restitution;                   // [-] in [0, 1]
  /// [m/s] World velocity of B's surface relative to A's (a conveyor belt under B moving at s
  /// gives -s): friction then sticks at v_B - v_A = -surfaceVelocity along the tangent plane.
  /// Its normal component is ignored; it acts only where friction > 0.
  Eigen::Vector3d surfaceVelocity;
  bool enabled;  // false: the pair exerts nothing this step (one-way platforms)
};

/// Called for every non-sensor manifold of the step, in manifold order (by collider pair), after
/// detection and before the islands are built: a contact turned off does not join islands. The
/// World may be read from inside (the velocities are this step's predicted v*), not changed.
/// A value out of range (NaN, friction < 0, restitution outside [0, 1]) is not used: the
/// material value stays and the step report gets a warning.
using PreSolveHook = std::function<void(ContactModification&)>;

/// Called for every candidate pair that passed the category/mask filters, every step (a pair
/// the filter refuses gets no manifold and no events); true keeps the pair.
using ContactFilter = std::function<bool(const geometry::Collider& a, const geometry::Collider& b)>;

}  // namespace coulomb::engine
