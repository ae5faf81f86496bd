#pragma once
// For each candidate pair, the raw contact (normal from A to B, candidate points, speculative
// points within the margin) turned into a manifold of <= 4 points. Closed forms for the pairs
// FCL gets wrong or answers with one point (PrimitiveContacts, BoxContacts); FCL (through
// FclScene, guarded) for the rest. A failing pair is reported and skipped.
#include <coulomb/geometry/Collider.hpp>
#include <coulomb/geometry/ContactManifold.hpp>
#include <coulomb/geometry/FclAdapter.hpp>
#include <coulomb/geometry/HullContacts.hpp>
#include <coulomb/geometry/ManifoldBuilder.hpp>
#include <coulomb/geometry/ParallelFor.hpp>

#include <memory>
#include <span>
#include <string>
#include <vector>

namespace coulomb::geometry {

/// Indices into the collider list, ordered so that colliders[a].id < colliders[b].id.
struct CandidatePair {
  std::size_t a = 0;
  std::size_t b = 0;
};

/// A problem with one pair (b valid) or one collider (b invalid), reported instead of thrown.
struct CollisionFailure {
  ColliderId a;
  ColliderId b;
  std::string message;
};

struct FeatureScratch;  // FeatureContacts.hpp

/// The closed forms' storage, kept by a NarrowPhase between pairs (one pair at a time).
struct NarrowPhaseScratch {
  HullScratch hulls;
  std::vector<Eigen::Vector3d> worldVertices;  // a hull's or mesh's against a plane
  // The feature manifolds' storage, made on first use. shared_ptr: its type stays private to
  // NarrowPhase.cpp (a copied NarrowPhase shares it; a NarrowPhase is used by one thread).
  std::shared_ptr<FeatureScratch> features;
};

/// One chunk of a step's pairs (NarrowPhase::collide): its scratch and its results, merged in
/// pair order afterwards, so that chunks can run on different threads.
struct NarrowPhaseChunk {
  PairContact pair;
  NarrowPhaseScratch scratch;
  std::string error;
  std::vector<ContactManifold> manifolds;
  std::vector<CollisionFailure> failures;
};

struct NarrowPhaseSettings {
  double margin = 0.005;     // [m] gaps below this still give (negative-depth) points
  int maxMeshContacts = 64;  // FCL stops mesh traversal at this count (docs/fcl-notes.md 4.4)
};

class NarrowPhase {
 public:
  explicit NarrowPhase(NarrowPhaseSettings settings = {}) : settings_(settings) {}

  /// Appends one manifold per touching pair to `out` (in the order of `pairs`) and one entry per
  /// failed pair to `failures`. `shapePoses` and `bodyPoses` are indexed like `colliders` and by
  /// BodyId.index respectively.
  /// `sweeps` (indexed like `colliders`; empty: none) widen each pair's margin to
  /// margin + sweeps[a] + sweeps[b] (velocity-swept speculative margin, SweptMargin.hpp).
  /// The pairs are taken in fixed chunks of consecutive pairs, each with a scratch of its own,
  /// run on `parallel`'s threads when given: the results do not depend on it.
  void collide(std::span<const CandidatePair> pairs, const std::vector<Collider>& colliders,
               std::span<const Pose> shapePoses, std::span<const Pose> bodyPoses,
               const FclScene& scene, std::vector<ContactManifold>& out,
               std::vector<CollisionFailure>& failures, std::span<const double> sweeps = {},
               const ParallelFor& parallel = {});

  /// Raw contact of one pair, normal from a to b (a.id < b.id). Returns false when the pair is
  /// farther apart than `margin` (default: the settings' margin); sets `error` (and returns
  /// false) when the pair failed.
  bool contactPair(const Collider& a, const Pose& poseA, const Collider& b, const Pose& poseB,
                   const FclScene& scene, PairContact& out, std::string& error) const {
    return contactPair(a, poseA, b, poseB, scene, out, error, settings_.margin);
  }
  bool contactPair(const Collider& a, const Pose& poseA, const Collider& b, const Pose& poseB,
                   const FclScene& scene, PairContact& out, std::string& error,
                   double margin) const {
    return contactPair(a, poseA, b, poseB, scene, out, error, margin, scratch_);
  }

  /// Test hook: called inside FCL's guarded region before each FCL query.
  void setFaultInjector(FclFaultInjector injector) { injector_ = std::move(injector); }
  [[nodiscard]] const NarrowPhaseSettings& settings() const { return settings_; }

 private:
  bool contactPair(const Collider& a, const Pose& poseA, const Collider& b, const Pose& poseB,
                   const FclScene& scene, PairContact& out, std::string& error, double margin,
                   NarrowPhaseScratch& scratch) const;
  // One candidate pair into `chunk` (its manifold or its failure).
  void collidePair(const CandidatePair& pair, const std::vector<Collider>& colliders,
                   std::span<const Pose> shapePoses, std::span<const Pose> bodyPoses,
                   const FclScene& scene, std::span<const double> sweeps,
                   NarrowPhaseChunk& chunk) const;
  bool viaFcl(const Collider& a, const Pose& poseA, const Collider& b, const Pose& poseB,
              const FclScene& scene, double margin, PairContact& out, std::string& error) const;
  // A mesh against a convex shape: every triangle near the shape, with FCL's normal where FCL
  // reports the triangle, the face normal on internal edges (MeshEdges.hpp).
  bool meshContact(const Collider& a, const Pose& poseA, const Collider& b, const Pose& poseB,
                   const FclScene& scene, double margin, PairContact& out, std::string& error,
                   NarrowPhaseScratch& scratch) const;

  NarrowPhaseSettings settings_;
  FclFaultInjector injector_;
  mutable NarrowPhaseScratch scratch_;    // contactPair's (queries, one pair at a time)
  std::vector<NarrowPhaseChunk> chunks_;  // collide's, kept for their storage
};

}  // namespace coulomb::geometry
