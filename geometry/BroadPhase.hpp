#pragma once
// Candidate pairs for the narrow phase: FCL's dynamic AABB tree (through FclScene, updated
// incrementally), planes tested separately (they crash the tree, docs/fcl-notes.md 4.8), then the
// filters: no pair within one body, category/mask bits, and a caller's predicate (e.g. skip
// bodies joined by a joint, or static-static pairs). Output sorted by (id of A, id of B).
#include <coulomb/geometry/Collider.hpp>
#include <coulomb/geometry/FclAdapter.hpp>
#include <coulomb/geometry/NarrowPhase.hpp>

#include <functional>
#include <span>
#include <vector>

namespace coulomb::geometry {

/// Returns true to keep the pair (a.id < b.id). Empty = keep every pair the filters accept.
using PairPredicate = std::function<bool(const Collider& a, const Collider& b)>;

class BroadPhase {
 public:
  /// Brings `scene` in line with `colliders` (new shapes built, removed colliders dropped, poses
  /// set), refits the tree and returns the filtered candidate pairs. Colliders with
  /// usable[i] == false are left out; a collider FCL rejects is reported and left out too.
  /// `sweeps[i]` [m] (empty: none) grows collider i's AABB beyond the margin, so every pair
  /// within margin + sweeps[a] + sweeps[b] is a candidate (SweptMargin.hpp).
  /// The returned pairs live until the next update (buffers reused: no allocation once sized).
  const std::vector<CandidatePair>& update(const std::vector<Collider>& colliders,
                                           std::span<const Pose> shapePoses,
                                           std::vector<char>& usable, FclScene& scene,
                                           double margin, const PairPredicate& keep,
                                           std::vector<CollisionFailure>& failures,
                                           std::span<const double> sweeps = {});

 private:
  std::size_t indexOf(ColliderId id) const;

  std::vector<std::pair<ColliderId, std::size_t>> indexById_;  // sorted by id
  // indexBySlot_[id.index]: the collider's position and generation, when the ids' slots are
  // dense (a World's are); else empty and indexOf searches indexById_.
  std::vector<std::pair<std::size_t, std::uint32_t>> indexBySlot_;
  std::vector<std::size_t> planes_, solids_;
  std::vector<std::pair<ColliderId, ColliderId>> ids_;
  std::vector<CandidatePair> pairs_;
};

}  // namespace coulomb::geometry
