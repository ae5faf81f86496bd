#include <coulomb/integrators/EnergyProjection.hpp>

#include <Eigen/Dense>

#include <cmath>

namespace coulomb::integrators {

BodyEnergy bodyEnergy(const geometry::BodyState& state, std::size_t body,
                      const Eigen::Vector3d& gravity) {
  if (!state.isDynamic(body) || !(state.inverseMasses[body] > 0.0)) return {};
  const double mass = 1.0 / state.inverseMasses[body];
  return {state.kineticEnergy(body) - mass * gravity.dot(state.poses[body].position),
          mass * gravity.dot(state.linearVelocities[body])};
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
                               double powerWeight) {
  EnergyProjection result;
  double current = 0.0;
  for (const std::int32_t i : bodies) {
    const BodyEnergy e = bodyEnergy(state, i, gravity);
    current += e.energy + powerWeight * e.gravityPower;
  }
  result.energyError = target - current;
  const RigidMotion rigid = anchored ? RigidMotion{} : rigidMotionOf(state, bodies);
  // E~(s) = a s^2 + b s + c for relative velocities scaled by s (the rigid part's energy and its
  // momentum term are in c; a free island's relative motion has no momentum, so b = 0 there).
  double a = 0.0, b = 0.0;
  for (const std::int32_t i : bodies) {
    const double m = 1.0 / state.inverseMasses[i];
    const Eigen::Vector3d v = state.linearVelocities[i] - rigid.velocityAt(state.poses[i].position);
    const Eigen::Vector3d w = state.angularVelocities[i] - rigid.angular;
    a += 0.5 * m * v.squaredNorm() + 0.5 * w.dot(worldInertia(state, i) * w);
    b += powerWeight * m * gravity.dot(v);
  }
  const double c = current - a - b;  // E~(1) = current
  const double discriminant = b * b - 4.0 * a * (c - target);
  if (!(a > 0.0) || !(discriminant >= 0.0)) return result;
  const double scale = (-b + std::sqrt(discriminant)) / (2.0 * a);
  if (!(std::abs(scale - 1.0) <= kMaxProjectionChange)) return result;
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
