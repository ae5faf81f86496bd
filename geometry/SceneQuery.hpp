#pragma once
// Scene queries between steps: ray casts (closest and all hits), shape casts (first hit of a
// swept sphere, box, capsule, cylinder or hull), overlap of a shape at a pose, AABB queries and
// the closest points of two colliders; each with category/mask bits and a predicate
// (docs/embedding.md, "Scene queries"). The query scene is its own copy of the colliders in
// FCL's tree, brought in line by sync(): only colliders whose shape or world pose changed are
// touched, so a sync between two queries of one step costs a comparison per collider.
// After sync(), the const queries only read: several threads may run them at once.
#include <coulomb/geometry/Collider.hpp>
#include <coulomb/geometry/FclAdapter.hpp>

#include <Eigen/Core>

#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <vector>

namespace coulomb::geometry {

/// Which colliders a query sees: those whose filter bits accept `bits` (the same rule as two
/// colliders: (bits.category & c.mask) != 0 && (c.category & bits.mask) != 0) and that `accept`
/// (empty: all) returns true for.
struct QueryFilter {
  CollisionFilter bits;
  std::function<bool(const Collider&)> accept;
};

struct RayHit {
  ColliderId collider;
  BodyId body;
  Eigen::Vector3d point = Eigen::Vector3d::Zero();    // world
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();  // outward surface normal, world, unit
  double fraction = 0.0;  // of the ray's translation: point = origin + fraction * translation
};

/// First contact of a swept shape: `fraction` of the translation at which it touches, the point
/// of contact on the hit collider and its surface normal there (pointing back at the shape).
struct ShapeHit {
  ColliderId collider;
  BodyId body;
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
  double fraction = 0.0;  // 0: the shape overlaps the collider at its start pose
};

struct ClosestPoints {
  /// [m] >= 0 when apart; when the colliders overlap, minus the penetration depth, with
  /// pointA = pointB = the deepest contact point.
  double distance = 0.0;
  Eigen::Vector3d pointA = Eigen::Vector3d::Zero();  // on collider a, world
  Eigen::Vector3d pointB = Eigen::Vector3d::Zero();  // on collider b, world
};

class SceneQuery {
 public:
  SceneQuery();
  ~SceneQuery();
  SceneQuery(SceneQuery&&) noexcept;
  SceneQuery& operator=(SceneQuery&&) noexcept;

  /// Brings the query scene in line with `colliders` posed by their bodies (`bodyPoses[k]` is
  /// the pose of the body with BodyId.index == k). A collider with a non-finite pose or an
  /// unknown body is left out of the queries.
  void sync(const std::vector<Collider>& colliders, std::span<const Pose> bodyPoses);

  /// The first collider the segment origin -> origin + translation meets. A ray starting
  /// inside a solid hits it at fraction 0 with normal -translation/|translation|; meshes are
  /// surfaces for rays. Ties go to the lower collider id. Throws std::invalid_argument for a
  /// non-finite origin or translation.
  [[nodiscard]] std::optional<RayHit> castRay(const Eigen::Vector3d& origin,
                                              const Eigen::Vector3d& translation,
                                              const QueryFilter& filter = {}) const;
  /// Every collider the segment meets (its first hit each), by fraction, then collider id.
  [[nodiscard]] std::vector<RayHit> castRayAll(const Eigen::Vector3d& origin,
                                               const Eigen::Vector3d& translation,
                                               const QueryFilter& filter = {}) const;
  /// The first collider that `shape` (sphere, box, capsule, cylinder or convex hull) touches
  /// when moved from `start` by `translation` without rotating; conservative advancement on
  /// FCL's distance to within kCastTolerance. Throws std::invalid_argument for another shape or
  /// a non-finite pose or translation.
  [[nodiscard]] std::optional<ShapeHit> castShape(const std::shared_ptr<const Shape>& shape,
                                                  const Pose& start,
                                                  const Eigen::Vector3d& translation,
                                                  const QueryFilter& filter = {}) const;
  /// Every collider that `shape` at `pose` overlaps (FCL collide), sorted by id.
  [[nodiscard]] std::vector<ColliderId> overlap(const std::shared_ptr<const Shape>& shape,
                                                const Pose& pose,
                                                const QueryFilter& filter = {}) const;
  /// Every collider whose tight world AABB overlaps `box` (planes: whose half-space reaches
  /// it), sorted by id.
  [[nodiscard]] std::vector<ColliderId> queryAabb(const Aabb& box,
                                                  const QueryFilter& filter = {}) const;
  /// Closest points of two colliders of the scene. Throws std::invalid_argument for an id that
  /// is not in the scene, two planes, or when FCL fails on the pair (its message).
  [[nodiscard]] ClosestPoints closestPoints(ColliderId a, ColliderId b) const;

  /// [m] A shape cast stops when the gap to the hit collider is below this.
  static constexpr double kCastTolerance = 1e-6;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace coulomb::geometry
