#pragma once
// Continuous collision for colliders of bodies that ask for it (BodyDesc::continuousCollision;
// Jolt's MotionQuality::LinearCast, Bullet's CCD). The speculative margins (SweptMargin.hpp)
// already stop fast *translating* bodies at whatever they approach; a fast *turning* body (a thin
// plank at 200 rad/s) is the case they miss, because the features closest at the start of the
// step are not the ones that meet: its tip sweeps an arc into a box beside it while the closest
// points, near its centre, barely move. Two parts (docs/collision.md, "Continuous collision"):
// - before the solve, each such pair gets its time of impact over the step (conservative
//   advancement, Mirtich 1996, along the poses v* predicts), and its manifold becomes one
//   speculative point at the features that touch then, placed where they are at the start of the
//   step, with the gap along the normal of impact as its speculative depth;
// - after the positions are integrated, the motion the body really takes (v+, which a turn of
//   radians per step does not follow linearly) is checked the same way, and a body that would
//   pass into a collider is stopped at its first touch, its velocities kept: the next step's
//   contact then meets the right features.
#include <coulomb/geometry/BodyState.hpp>
#include <coulomb/geometry/Collider.hpp>
#include <coulomb/geometry/ContactManifold.hpp>
#include <coulomb/geometry/FclAdapter.hpp>
#include <coulomb/geometry/SweptMargin.hpp>

#include <span>
#include <vector>

namespace coulomb::geometry {

/// The feature id of the point a time of impact gives (stable, so it warm-starts itself).
inline constexpr std::uint32_t kTimeOfImpactFeature = 0xC0C0C0C0u;

/// For every manifold with a continuous collider whose pair first touches at a time of impact
/// in (0, 1] of the step (a pair touching at the start keeps its manifold), replaces its points
/// by the point of impact. `byId` lists the indices of `colliders` sorted by id; `shapePoses`
/// are the colliders' world poses at the start of the step (as the scene holds them). A
/// continuous collider that is a plane or a mesh is not swept (no time of impact for them).
/// Returns how many manifolds were replaced.
int applyContinuousCollision(const std::vector<Collider>& colliders,
                             const std::vector<std::size_t>& byId, std::span<const Pose> shapePoses,
                             std::span<const Pose> bodyPoses, const SweepMotion& motion,
                             const FclScene& scene, double tolerance,
                             std::vector<ContactManifold>& manifolds);

/// After the positions are integrated: each dynamic body with a continuous collider whose motion
/// over the step (from `startBodyPoses`, at its velocities v+ for h seconds) touches a collider it
/// had a manifold with this step, at a fraction s in (0, 1], is put at its pose of first touch
/// (world inertia refreshed, velocities kept). Returns how many bodies were stopped.
std::size_t clampToTimeOfImpact(const std::vector<Collider>& colliders,
                                const std::vector<std::size_t>& byId,
                                std::span<const Pose> shapePoses,
                                std::span<const Pose> startBodyPoses, BodyState& state, double h,
                                const FclScene& scene, double tolerance,
                                std::vector<ContactManifold>& manifolds);

}  // namespace coulomb::geometry
