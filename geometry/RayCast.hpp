#pragma once
// Exact ray tests against each shape, in the shape's frame given by its world pose, and the
// support point of a shape (the point farthest along a direction). Used by the scene queries
// (SceneQuery.hpp); no FCL here (FCL 0.7 has no ray queries, docs/embedding.md "Scene queries").
#include <coulomb/geometry/Pose.hpp>
#include <coulomb/geometry/Shape.hpp>

#include <Eigen/Core>

#include <optional>

namespace coulomb::geometry {

/// Where a ray origin + t direction first meets a shape: t in [0, maxDistance] (direction is
/// unit, so t is a distance in metres) and the outward surface normal there, in world frame.
struct RayShapeHit {
  double distance = 0.0;
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
};

/// First hit of the ray with the solid shape at `shapePose`. `direction` must be unit length.
/// A ray that starts inside a solid (sphere, box, capsule, cylinder, hull, half-space) hits it
/// at distance 0 with normal -direction. A triangle mesh is a surface for rays: the first
/// triangle crossed, from either side, with the triangle's outward normal.
std::optional<RayShapeHit> rayCastShape(const Shape& shape, const Pose& shapePose,
                                        const Eigen::Vector3d& origin,
                                        const Eigen::Vector3d& direction, double maxDistance);

/// The point of the shape farthest along `direction` (any length, not zero), in the shape's
/// own frame. Planes have none (unbounded): this throws std::invalid_argument for them.
Eigen::Vector3d supportPoint(const Shape& shape, const Eigen::Vector3d& direction);

}  // namespace coulomb::geometry
