#pragma once
// The contact between two colliders: up to 4 points sharing one normal, plus the impulses of the
// last step for warm starting. Plain data (copyable, no pointers) so a snapshot can save it.
#include <coulomb/geometry/Ids.hpp>

#include <Eigen/Core>

#include <array>
#include <cstdint>
#include <span>

namespace coulomb::geometry {

struct ContactPoint {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();  // world, midway between the two surfaces
  double depth = 0.0;           // penetration [m]: > 0 overlapping, < 0 gap (speculative point)
  std::uint32_t featureId = 0;  // which features touch; stable while they keep touching
  Eigen::Vector3d localA = Eigen::Vector3d::Zero();  // `position` in body A's frame
  Eigen::Vector3d localB = Eigen::Vector3d::Zero();  // `position` in body B's frame
  double normalImpulse = 0.0;                        // last step's impulse along the normal [N s]
  Eigen::Vector2d tangentImpulse = Eigen::Vector2d::Zero();  // along tangent1, tangent2 [N s]
  bool warmStarted = false;  // true when the impulses were carried over from the last step
  // The normal row of the last solve at this point, carried over with the impulses (elastic
  // turning, engine/ContactSource.cpp and docs/tuning.md): its normal (zero: none), the
  // moments r_A x n and r_B x n of the normal about the body centres of that step, and the normal
  // velocity n . (v_B - v_A) the solve left there (exact, -bias, where it pushed; the approach
  // before the solve where it did not, which other points' impulses may have changed).
  Eigen::Vector3d solvedNormal = Eigen::Vector3d::Zero();
  Eigen::Vector3d solvedMomentA = Eigen::Vector3d::Zero();
  Eigen::Vector3d solvedMomentB = Eigen::Vector3d::Zero();
  double solvedNormalVelocity = 0.0;
  // [m/s] u_N = n . (v_B - v_A) at the point with v*, before this step's solve (written by the
  // contact row emission, read when the impulses are stored; not carried between steps).
  double approachVelocity = 0.0;
};

struct ContactManifold {
  static constexpr int kMaxPoints = 4;

  ColliderId colliderA;  // colliderA < colliderB always
  ColliderId colliderB;
  BodyId bodyA;
  BodyId bodyB;
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();    // unit, from A to B
  Eigen::Vector3d tangent1 = Eigen::Vector3d::UnitX();  // (normal, tangent1, tangent2) right-handed
  Eigen::Vector3d tangent2 = Eigen::Vector3d::UnitY();
  double friction = 0.5;     // sqrt(mu_a mu_b)
  double restitution = 0.0;  // max(e_a, e_b)
  std::array<ContactPoint, kMaxPoints> points{};
  int pointCount = 0;
  // Set fresh every step by the manifold builder, changed only by the World's pre-solve hook
  // (engine/ContactHooks.hpp); not carried between steps.
  bool sensor = false;  // a sensor is in the pair: reported, never solved
  bool enabled = true;  // false: no rows this step (the hook turned the contact off)
  /// [m/s] World velocity of B's surface relative to A's (a conveyor belt, a tank track): the
  /// friction rows drive t . (v_B - v_A + surfaceVelocity) to zero instead of t . (v_B - v_A).
  Eigen::Vector3d surfaceVelocity = Eigen::Vector3d::Zero();

  [[nodiscard]] std::span<ContactPoint> activePoints() {
    return {points.data(), static_cast<std::size_t>(pointCount)};
  }
  [[nodiscard]] std::span<const ContactPoint> activePoints() const {
    return {points.data(), static_cast<std::size_t>(pointCount)};
  }
};

/// Deterministic orthonormal tangents for a unit normal n, with n x t1 = t2 (a pure function of n,
/// so the frame never depends on the order points were found in). Duff et al., "Building an
/// Orthonormal Basis, Revisited", JCGT 6(1), 2017, listing 3.
inline void makeTangentFrame(const Eigen::Vector3d& n, Eigen::Vector3d& t1, Eigen::Vector3d& t2) {
  const double sign = n.z() >= 0.0 ? 1.0 : -1.0;
  const double a = -1.0 / (sign + n.z());
  const double b = n.x() * n.y() * a;
  t1 = Eigen::Vector3d(1.0 + sign * n.x() * n.x() * a, sign * b, -sign * n.x());
  t2 = Eigen::Vector3d(b, sign + n.y() * n.y() * a, -n.y());
}

}  // namespace coulomb::geometry
