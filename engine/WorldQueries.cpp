#include <coulomb/engine/WorldQueries.hpp>

#include <coulomb/engine/CoulombError.hpp>

#include <stdexcept>

namespace coulomb::engine {
namespace {

// The geometry layer refuses bad input with std::invalid_argument; the engine's one error type
// for bad input is CoulombError (same message).
template <class Query>
auto refusing(const Query& query) {
  try {
    return query();
  } catch (const std::invalid_argument& error) {
    throw CoulombError(error.what());
  }
}

}  // namespace

const geometry::SceneQuery& WorldQueries::synced() {
  query_.sync(world_->colliders(), world_->state().poses);
  return query_;
}

std::optional<geometry::RayHit> WorldQueries::castRay(const Eigen::Vector3d& origin,
                                                      const Eigen::Vector3d& translation,
                                                      const geometry::QueryFilter& filter) {
  return refusing([&] { return synced().castRay(origin, translation, filter); });
}

std::vector<geometry::RayHit> WorldQueries::castRayAll(const Eigen::Vector3d& origin,
                                                       const Eigen::Vector3d& translation,
                                                       const geometry::QueryFilter& filter) {
  return refusing([&] { return synced().castRayAll(origin, translation, filter); });
}

std::optional<geometry::ShapeHit> WorldQueries::castShape(
    const std::shared_ptr<const geometry::Shape>& shape, const geometry::Pose& start,
    const Eigen::Vector3d& translation, const geometry::QueryFilter& filter) {
  return refusing([&] { return synced().castShape(shape, start, translation, filter); });
}

std::vector<geometry::ColliderId> WorldQueries::overlap(
    const std::shared_ptr<const geometry::Shape>& shape, const geometry::Pose& pose,
    const geometry::QueryFilter& filter) {
  return refusing([&] { return synced().overlap(shape, pose, filter); });
}

std::vector<geometry::ColliderId> WorldQueries::queryAabb(const geometry::Aabb& box,
                                                          const geometry::QueryFilter& filter) {
  return refusing([&] { return synced().queryAabb(box, filter); });
}

geometry::ClosestPoints WorldQueries::closestPoints(geometry::ColliderId a,
                                                    geometry::ColliderId b) {
  return refusing([&] { return synced().closestPoints(a, b); });
}

}  // namespace coulomb::engine
