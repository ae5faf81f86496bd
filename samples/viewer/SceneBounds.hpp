#pragma once
// What the automatic camera frames: a sphere around the scene's bodies.
#include <coulomb/engine/World.hpp>

#include <Eigen/Core>

namespace coulomb::viewer {

struct BoundingSphere {
  Eigen::Vector3d center = Eigen::Vector3d::Zero();
  double radius = 1.0;  // [m]
};

/// The box around every collider of the dynamic and kinematic bodies (robot links are kinematic
/// proxies) and around the static colliders that are props rather than ground (each bounding
/// radius under 10 m: the double loop's 1720 rail capsules count, a 50 m floor box or a plane
/// does not), as a sphere. A world without any gives a 1 m sphere at the origin.
BoundingSphere sceneBounds(const engine::World& world);

}  // namespace coulomb::viewer
