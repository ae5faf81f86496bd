#pragma once
// Scene queries on a World between steps (docs/embedding.md, "Scene queries"): ray casts, shape
// casts, overlaps, AABB queries and closest points of the World's colliders where they are now.
// Each call first brings its query scene in line with the World (geometry::SceneQuery::sync:
// a comparison per collider when only poses changed), so queries always see the current state.
// Bad input (non-finite vectors, a plane as a query shape, an unknown collider) throws
// CoulombError. One WorldQueries per thread that queries; none may run while the World steps.
#include <coulomb/engine/World.hpp>
#include <coulomb/geometry/SceneQuery.hpp>

namespace coulomb::engine {

class WorldQueries {
 public:
  explicit WorldQueries(const World& world) : world_(&world) {}

  [[nodiscard]] std::optional<geometry::RayHit> castRay(const Eigen::Vector3d& origin,
                                                        const Eigen::Vector3d& translation,
                                                        const geometry::QueryFilter& filter = {});
  [[nodiscard]] std::vector<geometry::RayHit> castRayAll(const Eigen::Vector3d& origin,
                                                         const Eigen::Vector3d& translation,
                                                         const geometry::QueryFilter& filter = {});
  [[nodiscard]] std::optional<geometry::ShapeHit> castShape(
      const std::shared_ptr<const geometry::Shape>& shape, const geometry::Pose& start,
      const Eigen::Vector3d& translation, const geometry::QueryFilter& filter = {});
  [[nodiscard]] std::vector<geometry::ColliderId> overlap(
      const std::shared_ptr<const geometry::Shape>& shape, const geometry::Pose& pose,
      const geometry::QueryFilter& filter = {});
  [[nodiscard]] std::vector<geometry::ColliderId> queryAabb(
      const geometry::Aabb& box, const geometry::QueryFilter& filter = {});
  [[nodiscard]] geometry::ClosestPoints closestPoints(geometry::ColliderId a,
                                                      geometry::ColliderId b);

  /// The synced query scene, for many queries at one state (its const queries may then run on
  /// several threads at once).
  [[nodiscard]] const geometry::SceneQuery& synced();

 private:
  const World* world_;
  geometry::SceneQuery query_;
};

}  // namespace coulomb::engine
