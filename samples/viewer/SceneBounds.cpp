#include "SceneBounds.hpp"

#include <coulomb/geometry/SweptMargin.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace coulomb::viewer {

BoundingSphere sceneBounds(const engine::World& world) {
  constexpr double kPropRadius = 10.0;  // [m] larger static colliders are ground, not framed
  const geometry::BodyState& state = world.state();
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector3d hi = -lo;
  for (const geometry::Collider& c : world.colliders()) {
    const std::size_t i = c.body.index;
    if (i >= state.size() || state.alive[i] == 0 || !c.shape) continue;
    const double r = geometry::boundingRadius(*c.shape);
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
