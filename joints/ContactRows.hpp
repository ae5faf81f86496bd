#pragma once
// Contact rows: one Contact3D block per manifold point (normal, tangent1, tangent2), or a single
// Unilateral normal row when mu = 0 (model only what the scene needs).
#include <coulomb/joints/RowBlock.hpp>

#include <Eigen/Core>

namespace coulomb::joints {

/// One contact point as the row emitter needs it: world point, unit normal from A to B, an
/// orthonormal tangent frame, and each body's centre of mass (an invalid body id = the world).
struct ContactPointFrame {
  geometry::BodyId bodyA;
  geometry::BodyId bodyB;
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
  Eigen::Vector3d tangent1 = Eigen::Vector3d::UnitX();
  Eigen::Vector3d tangent2 = Eigen::Vector3d::UnitY();
  Eigen::Vector3d centreA = Eigen::Vector3d::Zero();
  Eigen::Vector3d centreB = Eigen::Vector3d::Zero();
  double friction = 0.0;
  double normalVelocityBias = 0.0;  // added to u_N: restitution target and/or stabilisation
  /// Added to u_T1, u_T2 (a moving surface; ContactManifold::surfaceVelocity): friction then
  /// sticks at t . (v_B - v_A) = -bias instead of 0.
  Eigen::Vector2d tangentVelocityBias = Eigen::Vector2d::Zero();
  std::uint64_t key = 0;
};

/// u = J_A t_A + J_B t_B with u_N = n . (v_B(p) - v_A(p)) > 0 when separating, where
/// v_X(p) = v_X + w_X x (p - c_X); hence the row for direction d is
/// J_A = -(d^T, ((p - c_A) x d)^T), J_B = +(d^T, ((p - c_B) x d)^T).
RowBlock makeContactRows(const ContactPointFrame& contact);

}  // namespace coulomb::joints
