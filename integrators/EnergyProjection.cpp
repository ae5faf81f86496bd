#include <coulomb/integrators/EnergyProjection.hpp>

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>

namespace coulomb::integrators {

double bodyEnergy(const geometry::BodyState& state, std::size_t body,
                  const Eigen::Vector3d& gravity) {
  if (!state.isDynamic(body) || !(state.inverseMasses[body] > 0.0)) return 0.0;
  return state.kineticEnergy(body) -
         gravity.dot(state.poses[body].position) / state.inverseMasses[body];
}

namespace {

struct RigidMotion {  // the island's velocity field as one rigid body: V + Omega x (x - c)
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  Eigen::Vector3d linear = Eigen::Vector3d::Zero();
  Eigen::Vector3d angular = Eigen::Vector3d::Zero();
  [[nodiscard]] Eigen::Vector3d velocityAt(const Eigen::Vector3d& x) const {
    return linear + angular.cross(x - centre);
  }
};

Eigen::Matrix3d worldInertia(const geometry::BodyState& state, std::size_t i) {
  const Eigen::Matrix3d r = (state.poses[i].rotation * state.principalFrames[i]).toRotationMatrix();
  return r * state.principalMoments[i].asDiagonal() * r.transpose();
}

// The rigid motion with the island's momentum and angular momentum about its centre of mass: the
// projection of the velocities onto rigid motions in the kinetic metric, so the rest carries
// neither momentum nor angular momentum and its kinetic energy adds to the rigid motion's.
RigidMotion rigidMotionOf(const geometry::BodyState& state, std::span<const std::int32_t> bodies) {
  RigidMotion rigid;
  double mass = 0.0;
  Eigen::Vector3d momentum = Eigen::Vector3d::Zero();
  for (const std::int32_t i : bodies) {
    const double m = 1.0 / state.inverseMasses[i];
    mass += m;
    rigid.centre += m * state.poses[i].position;
    momentum += m * state.linearVelocities[i];
  }
  rigid.centre /= mass;
  rigid.linear = momentum / mass;
  Eigen::Vector3d angularMomentum = Eigen::Vector3d::Zero();
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();
  for (const std::int32_t i : bodies) {
    const double m = 1.0 / state.inverseMasses[i];
    const Eigen::Vector3d r = state.poses[i].position - rigid.centre;
    angularMomentum += r.cross(m * state.linearVelocities[i]) + state.angularMomentum(i);
    inertia += worldInertia(state, i) +
               m * (r.squaredNorm() * Eigen::Matrix3d::Identity() - r * r.transpose());
  }
  rigid.angular = inertia.ldlt().solve(angularMomentum);
  return rigid;
}

}  // namespace

EnergyProjection projectEnergy(geometry::BodyState& state, std::span<const std::int32_t> bodies,
                               bool anchored, double target, const Eigen::Vector3d& gravity,
                               double powerWeight, std::span<const Eigen::Vector3d> powerVelocities,
                               double resolution) {
  const auto u = [&](std::int32_t i) -> const Eigen::Vector3d& {
    return powerVelocities.empty() ? state.linearVelocities[i] : powerVelocities[i];
  };
  EnergyProjection result;
  double current = 0.0;
  for (const std::int32_t i : bodies)
    current +=
        bodyEnergy(state, i, gravity) + powerWeight * gravity.dot(u(i)) / state.inverseMasses[i];
  result.energyError = target - current;
  // Within the joints' resolution there is nothing to restore; a non-finite energy (a body the
  // World's guard is about to isolate) gives no factor either.
  if (!std::isfinite(result.energyError) || std::abs(result.energyError) <= resolution)
    return result;
  const RigidMotion rigid = anchored ? RigidMotion{} : rigidMotionOf(state, bodies);
  // E~(s) = a s^2 + b s + c for relative velocities scaled by s (the rigid part's energy and its
  // power term are in c). u of a rigid motion is that motion's velocity field, and u is linear in
  // the velocities, so the relative part of u scales with s too.
  double a = 0.0, b = 0.0;
  for (const std::int32_t i : bodies) {
    const double m = 1.0 / state.inverseMasses[i];
    const Eigen::Vector3d rigidVelocity = rigid.velocityAt(state.poses[i].position);
    const Eigen::Vector3d v = state.linearVelocities[i] - rigidVelocity;
    const Eigen::Vector3d w = state.angularVelocities[i] - rigid.angular;
    a += 0.5 * m * v.squaredNorm() + 0.5 * w.dot(worldInertia(state, i) * w);
    b += powerWeight * m * gravity.dot(u(i) - rigidVelocity);
  }
  const double c = current - a - b;  // E~(1) = current
  if (!(a > 0.0)) return result;     // nothing moves relative to the rigid motion
  // The larger root of E~(s) = target; below the parabola's vertex, the vertex (the nearest).
  const double discriminant = b * b - 4.0 * a * (c - target);
  const double root =
      discriminant >= 0.0 ? (-b + std::sqrt(discriminant)) / (2.0 * a) : -b / (2.0 * a);
  if (!std::isfinite(root)) return result;
  const double scale = std::clamp(root, kMinProjectionScale, kMaxProjectionScale);
  result.partial = scale != root || discriminant < 0.0;
  for (const std::int32_t i : bodies) {
    const Eigen::Vector3d base = rigid.velocityAt(state.poses[i].position);
    state.linearVelocities[i] = base + scale * (state.linearVelocities[i] - base);
    state.angularVelocities[i] =
        rigid.angular + scale * (state.angularVelocities[i] - rigid.angular);
  }
  result.applied = true;
  result.scale = scale;
  return result;
}

}  // namespace coulomb::integrators
