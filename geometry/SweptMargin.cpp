#include <coulomb/geometry/SweptMargin.hpp>

#include <algorithm>
#include <cmath>

namespace coulomb::geometry {
namespace {

double farthestVertex(const std::vector<Eigen::Vector3d>& vertices) {
  double r = 0.0;
  for (const Eigen::Vector3d& v : vertices) r = std::max(r, v.norm());
  return r;
}

}  // namespace

double rotationReach(const Shape& shape) {
  // A sphere turning about its centre covers the same points, and a capsule's rounding radius
  // adds nothing either: only the core (centre, segment) moves the surface.
  if (const auto* capsule = std::get_if<Capsule>(&shape)) return capsule->halfLength;
  if (std::holds_alternative<Sphere>(shape)) return 0.0;
  return boundingRadius(shape);
}

double boundingRadius(const Shape& shape) {
  switch (shape.index()) {
    case 0:
      return std::get<Sphere>(shape).radius;
    case 1:
      return std::get<Box>(shape).halfExtents.norm();
    case 2: {
      const Capsule& c = std::get<Capsule>(shape);
      return c.halfLength + c.radius;
    }
    case 3: {
      const Cylinder& c = std::get<Cylinder>(shape);
      return std::hypot(c.halfLength, c.radius);
    }
    case 5:
      return farthestVertex(std::get<ConvexHull>(shape).vertices);
    case 6:
      return farthestVertex(std::get<TriangleMesh>(shape).vertices);
    default:
      return 0.0;  // plane
  }
}

void colliderSweeps(const std::vector<Collider>& colliders, const std::vector<char>& usable,
                    const SweepMotion& motion, double factor, std::vector<double>& out) {
  out.assign(colliders.size(), 0.0);
  if (!(factor > 0.0) || !(motion.h > 0.0)) return;
  for (std::size_t i = 0; i < colliders.size(); ++i) {
    const Collider& c = colliders[i];
    const std::uint32_t body = c.body.index;
    if (!usable[i] || !c.shape || body >= motion.linearVelocities.size() ||
        body >= motion.angularVelocities.size())
      continue;
    const double speed = motion.linearVelocities[body].norm();
    const double spin = motion.angularVelocities[body].norm();
    // Meshes and hulls cost a pass over their vertices: only when the body turns.
    const double reach = spin > 0.0 ? c.localPose.position.norm() + rotationReach(*c.shape) : 0.0;
    const double sweep = factor * motion.h * (speed + spin * reach);
    if (std::isfinite(sweep)) out[i] = sweep;
  }
}

}  // namespace coulomb::geometry
