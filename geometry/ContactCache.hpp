#pragma once
// Manifolds that persist from step to step. Each new point takes over the impulses of the old
// point it matches (same feature id, else the nearest old anchor within `matchDistance`), so the
// solver can warm start; a one-point manifold of a new collider pair takes over an ended one of the
// same bodies and one common collider (a ball rolling from capsule to capsule of a rail). Plain
// data: a snapshot saves manifolds() and restore() puts it back.
#include <coulomb/geometry/ContactManifold.hpp>
#include <coulomb/geometry/Pose.hpp>

#include <span>
#include <vector>

namespace coulomb::geometry {

struct ContactCacheSettings {
  double matchDistance = 0.002;   // [m] proximity match for points whose feature id changed
  double normalAgreement = 0.95;  // min n_old . n_new to carry impulses (docs/fcl-notes.md 9)
};

class ContactCache {
 public:
  explicit ContactCache(ContactCacheSettings settings = {}) : settings_(settings) {}

  /// Replaces the cached manifolds by `fresh` (any order), carrying impulses over from matching
  /// points of the last step. `bodyPoses` (by BodyId.index) place the old anchors. The vectors are
  /// swapped: on return `fresh` holds the previous manifolds, so the caller reuses its buffer
  /// (10 000 spheres make ~35 MB of manifolds per step; reallocating them was a tenth of a step).
  const std::vector<ContactManifold>& refresh(std::vector<ContactManifold>& fresh,
                                              std::span<const Pose> bodyPoses);

  /// Sorted by (colliderA, colliderB). The solver writes the impulses it applied back here.
  [[nodiscard]] std::vector<ContactManifold>& manifolds() { return manifolds_; }
  [[nodiscard]] const std::vector<ContactManifold>& manifolds() const { return manifolds_; }
  /// Snapshot restore: takes a copy of a previously saved manifolds() vector.
  void restore(std::vector<ContactManifold> saved);
  void clear() { manifolds_.clear(); }

 private:
  /// Warm start of one-point manifolds whose collider pair is new (`orphans`, indices into
  /// `fresh`) from an ended one-point manifold of the same two bodies sharing one collider, with
  /// the closest normal (at least normalAgreement).
  void handOver(std::vector<ContactManifold>& fresh, std::span<const std::size_t> orphans,
                const std::vector<char>& continued) const;

  ContactCacheSettings settings_;
  std::vector<ContactManifold> manifolds_;
  std::vector<char> continued_;       // refresh(): old manifolds matched this step
  std::vector<std::size_t> orphans_;  // refresh(): fresh one-point manifolds of new pairs
};

}  // namespace coulomb::geometry
