#pragma once
// The collision stage of World::step in one call: colliders + body poses in, persistent
// manifolds (warm starts carried) and per-pair diagnostics out. Deterministic: the same input
// gives the same manifolds in the same order, whatever FCL's internal tree order is.
#include <coulomb/geometry/BodyState.hpp>
#include <coulomb/geometry/BroadPhase.hpp>
#include <coulomb/geometry/Collider.hpp>
#include <coulomb/geometry/ContactCache.hpp>
#include <coulomb/geometry/ContactManifold.hpp>
#include <coulomb/geometry/FclAdapter.hpp>
#include <coulomb/geometry/NarrowPhase.hpp>
#include <coulomb/geometry/ParallelFor.hpp>
#include <coulomb/geometry/SweptMargin.hpp>

#include <algorithm>
#include <optional>
#include <span>
#include <string>
#include <tuple>
#include <vector>

namespace coulomb::geometry {

struct CollisionSettings {
  /// [m] Points closer than this are kept with a negative depth (speculative contacts), and
  /// AABBs are fattened by it, so a resting contact does not flicker on and off.
  double speculativeMargin = 0.005;
  /// [-] Velocity sweep of the margin: a pair's margin grows by this factor times the distance
  /// its bodies can travel in the step, h (|v_A| + |w_A| r_A + |v_B| + |w_B| r_B) (v* of the
  /// step; SweptMargin.hpp), so bodies approaching faster than margin/h still get their contact
  /// rows before they meet. Default 1: exactly the travel; 0: the fixed margin alone (the
  /// behaviour before; a box pile then sinks 5 cm into its floor, docs/conformance.md).
  double speculativeSweep = 1.0;
  /// [m] Distance within which a point whose feature id changed still inherits the old impulses.
  double matchDistance = 0.002;
  /// Contacts FCL may report per mesh pair before it stops (it truncates, docs/fcl-notes.md 4.4).
  int maxMeshContacts = 64;

  bool operator==(const CollisionSettings&) const = default;
};

struct CollisionStats {
  std::size_t candidatePairs = 0;  // after filters
  std::size_t touchingPairs = 0;   // manifolds
  std::size_t contactPoints = 0;
};

struct CollisionDiagnostics {
  std::vector<CollisionFailure> failures;  // skipped pairs/colliders with the reason
  CollisionStats stats;
};

class CollisionPipeline {
 public:
  explicit CollisionPipeline(CollisionSettings settings = {});

  /// One collision step. `bodyPoses[k]` is the pose of the body with BodyId.index == k and
  /// `motion` its velocities over the step (sweeps the margins; empty: the fixed margin).
  /// A collider with a bad shape, an unknown body or a non-finite pose is skipped and reported;
  /// a pair FCL fails on is skipped and reported; nothing throws.
  /// `parallel` (empty: none) runs the narrow phase's pairs on the caller's threads; the
  /// manifolds are the same, bit for bit, with or without it (NarrowPhase::collide).
  const std::vector<ContactManifold>& step(const std::vector<Collider>& colliders,
                                           std::span<const Pose> bodyPoses,
                                           const SweepMotion& motion,
                                           const PairPredicate& keepPair = {},
                                           const ParallelFor& parallel = {});
  /// The same with the fixed margin alone (no velocities).
  const std::vector<ContactManifold>& step(const std::vector<Collider>& colliders,
                                           std::span<const Pose> bodyPoses,
                                           const PairPredicate& keepPair = {}) {
    return step(colliders, bodyPoses, SweepMotion{}, keepPair);
  }

  /// After the positions of the step are integrated: stops each body with a continuous collider
  /// at its first touch with a collider it had a manifold with in this step's step() call
  /// (ContinuousCollision.hpp). Returns how many bodies were stopped; 0 at no cost when no
  /// collider is continuous.
  std::size_t clampContinuous(const std::vector<Collider>& colliders, BodyState& state, double h);

  [[nodiscard]] const CollisionDiagnostics& diagnostics() const { return diagnostics_; }
  /// Persistent manifolds; the solver writes applied impulses into their points.
  [[nodiscard]] ContactCache& cache() { return cache_; }
  [[nodiscard]] const ContactCache& cache() const { return cache_; }
  [[nodiscard]] const CollisionSettings& settings() const { return settings_; }

  /// Test hook: runs inside the guarded region of every FCL query (throw to simulate FCL failing).
  void setFaultInjector(FclFaultInjector injector) {
    narrowPhase_.setFaultInjector(std::move(injector));
  }

  /// [m] The gap at which a pair of a continuous collider counts as touching: a fifth of the
  /// margin (1 mm by default), since its speculative row covers the rest.
  [[nodiscard]] double continuousTolerance() const {
    return std::max(1e-4, 0.2 * settings_.speculativeMargin);
  }

  /// The check to run when a collider is created: a message naming the problem, or nullopt.
  static std::optional<std::string> validateCollider(const Collider& collider);

 private:
  CollisionSettings settings_;
  FclScene scene_;
  BroadPhase broadPhase_;
  NarrowPhase narrowPhase_;
  ContactCache cache_;
  CollisionDiagnostics diagnostics_;
  std::vector<Pose> shapePoses_;
  std::vector<Pose> startBodyPoses_;  // the body poses of the last step(), when some collider is
                                      // continuous (clampContinuous)
  bool anyContinuous_ = false;
  std::vector<char> usable_;
  std::vector<double> sweeps_;  // [m] per collider (SweptMargin.hpp)
  std::vector<ContactManifold> fresh_;
  std::vector<std::size_t> order_;  // colliders by id (duplicate check)
  std::vector<std::tuple<ColliderId, BodyId, std::size_t>> capsuleEndKeys_;
};

}  // namespace coulomb::geometry
