#include "SceneBounds.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <type_traits>
#include <variant>

namespace coulomb::viewer {
namespace {

double farthestVertex(const std::vector<Eigen::Vector3d>& vertices) {
  double r = 0.0;
  for (const Eigen::Vector3d& v : vertices) r = std::max(r, v.norm());
  return r;
}

}  // namespace

double shapeRadius(const geometry::Shape& shape) {
  return std::visit(
      [](const auto& s) -> double {
        using T = std::decay_t<decltype(s)>;
        if constexpr (std::is_same_v<T, geometry::Sphere>) return s.radius;
        if constexpr (std::is_same_v<T, geometry::Box>) return s.halfExtents.norm();
        if constexpr (std::is_same_v<T, geometry::Capsule>) return s.radius + s.halfLength;
        if constexpr (std::is_same_v<T, geometry::Cylinder>)
          return std::hypot(s.radius, s.halfLength);
        if constexpr (std::is_same_v<T, geometry::Plane>) return 0.0;
        if constexpr (std::is_same_v<T, geometry::ConvexHull> ||
                      std::is_same_v<T, geometry::TriangleMesh>)
          return farthestVertex(s.vertices);
        return 0.0;
      },
      shape);
}

BoundingSphere sceneBounds(const engine::World& world) {
  constexpr double kPropRadius = 10.0;  // [m] larger static colliders are ground, not framed
  const geometry::BodyState& state = world.state();
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector3d hi = -lo;
  for (const geometry::Collider& c : world.colliders()) {
    const std::size_t i = c.body.index;
    if (i >= state.size() || state.alive[i] == 0 || !c.shape) continue;
    const double r = shapeRadius(*c.shape);
    if (r <= 0.0) continue;  // planes
    if (state.motionTypes[i] == geometry::MotionType::Static && r > kPropRadius) continue;
    const Eigen::Vector3d p = (state.poses[i] * c.localPose).position;
    if (!p.allFinite()) continue;
    lo = lo.cwiseMin(p - Eigen::Vector3d::Constant(r));
    hi = hi.cwiseMax(p + Eigen::Vector3d::Constant(r));
  }
  if (!(lo.array() <= hi.array()).all()) return {};
  return {0.5 * (lo + hi), std::max(0.5 * (hi - lo).norm(), 0.05)};
}

}  // namespace coulomb::viewer
