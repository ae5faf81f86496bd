#pragma once
// A ball on a chain of capsules (a rail, a rope of static segments) touches the chain at one point,
// but every capsule within the speculative margin gives its own contact: the nearest point of a
// capsule ahead or behind is the end it shares with its neighbour, with a normal tilted toward
// that end. Those end-cap points are ghosts: the end cap lies inside the neighbour capsule, so the
// point adds no constraint the neighbour's contact does not already give, and its linearised gap
// (u_N >= -gap/h along the tilted normal) stops a ball rolling along the chain as if it hit a step
// (measured on docs/scene-specifications.md B11 double_loop: the ball lost a third of its speed and
// lifted off the rails). This pass drops them.
#include <coulomb/geometry/Collider.hpp>
#include <coulomb/geometry/ContactManifold.hpp>
#include <coulomb/geometry/Pose.hpp>

#include <span>
#include <tuple>
#include <vector>

namespace coulomb::geometry {

/// Removes every sphere-capsule manifold whose point is on an end cap of the capsule (the
/// sphere's centre projects beyond the segment) when that end cap lies inside another capsule of
/// the same body touching the same sphere with a smaller gap (ties: the lower collider id is
/// kept). Exact, not a heuristic: the removed cap is a subset of the capsule kept, so the
/// distance to the body is unchanged. `shapePoses` are the colliders' world poses, parallel to
/// `colliders`; the manifolds keep their order.
/// `keys`: the cheap first test's list, kept by the caller for its storage (null: a local one).
void dropCoveredCapsuleEnds(
    const std::vector<Collider>& colliders, std::span<const Pose> shapePoses,
    std::vector<ContactManifold>& manifolds,
    std::vector<std::tuple<ColliderId, BodyId, std::size_t>>* keys = nullptr);

}  // namespace coulomb::geometry
