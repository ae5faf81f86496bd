#pragma once
// A collider is a shape attached to a body at a local pose, with a material and filter bits.
// The collision layer (BroadPhase, NarrowPhase, ManifoldBuilder, ContactCache) consumes colliders
// plus the body poses; it never sees velocities or masses.
#include <coulomb/geometry/Ids.hpp>
#include <coulomb/geometry/Pose.hpp>
#include <coulomb/geometry/Shape.hpp>

#include <cstdint>
#include <memory>

namespace coulomb::geometry {

struct Material {
  double friction = 0.5;     // Coulomb coefficient mu [-]; a pair uses sqrt(mu_a * mu_b)
  double restitution = 0.0;  // Newton restitution e in [0, 1]; a pair uses max(e_a, e_b)
};

/// Category/mask filtering: colliders a and b may touch iff
/// (a.category & b.mask) != 0 && (b.category & a.mask) != 0.
struct CollisionFilter {
  std::uint32_t category = 1u;
  std::uint32_t mask = 0xffffffffu;
  [[nodiscard]] bool accepts(const CollisionFilter& other) const {
    return (category & other.mask) != 0 && (other.category & mask) != 0;
  }
};

struct Collider {
  ColliderId id;
  BodyId body;                         // owning body; index into the body state arrays
  Pose localPose;                      // shape frame in the body frame
  std::shared_ptr<const Shape> shape;  // shared: many colliders may use one mesh
  Material material;
  CollisionFilter filter;
  /// Time of impact over each step against what it may touch (ContinuousCollision.hpp); set
  /// from BodyDesc::continuousCollision for every collider of the body.
  bool continuous = false;
  /// A sensor (trigger volume) is detected like any collider but never pushes: its pairs give
  /// overlap begin/end events (engine/ContactEvents.hpp) and no contact rows. Two sensors never
  /// pair.
  bool sensor = false;
  /// The user's value (an index, a handle, a pointer cast to an integer); never read by the engine.
  std::uint64_t userData = 0;
};

}  // namespace coulomb::geometry
