#pragma once
// A block of constraint rows between two bodies, in body twist coordinates.
//
// Twist convention (used by every row emitter, the assembler and the impulse applier): a body's
// twist is the 6-vector (v, w) = (linear velocity of the centre of mass, angular velocity), both
// in world coordinates. A block of k rows relates the twists to the constraint-space velocity
//     u = J_A (v_A, w_A) + J_B (v_B, w_B) + bias                           (k rows)
// and its impulse lambda (k) acts on the bodies as  dP_A = J_A^T lambda,  dP_B = J_B^T lambda
// (generalised impulses (linear, angular) about each COM). Survey (Bender et al. 2014) sec. 3.
//
// Kinds follow solvers::ContactProblem's blocks (the assembler translates them one to one):
//   Equality   u = 0, lambda free                                  (joints)
//   Bounded    lower <= lambda <= upper with the box complementarity  (motors, joint friction)
//   Unilateral u >= 0, lambda >= 0, u lambda = 0                      (limits, frictionless
//   contact) Contact3D  rows (normal, tangent1, tangent2); lambda in the Coulomb cone of
//   `friction`,
//              De Saxce complementarity. Never split into independent rows (golden rule 5).
#include <coulomb/geometry/Ids.hpp>

#include <Eigen/Core>

#include <cstdint>

namespace coulomb::joints {

enum class RowKind : std::uint8_t { Equality, Bounded, Unilateral, Contact3D };

using RowJacobian = Eigen::Matrix<double, Eigen::Dynamic, 6, Eigen::RowMajor, 6, 6>;
using RowVector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 6, 1>;

struct RowBlock {
  RowKind kind = RowKind::Equality;
  geometry::BodyId bodyA;  // invalid id = the world (no unknowns)
  geometry::BodyId bodyB;
  RowJacobian jacobianA;  // k x 6
  RowJacobian jacobianB;  // k x 6
  RowVector bias;         // k: velocity offset (restitution target, stabilisation), [m/s or rad/s]
  RowVector lower;        // k: Bounded only [N s]
  RowVector upper;        // k: Bounded only [N s]
  double friction = 0.0;  // Contact3D only: Coulomb coefficient mu
  std::uint64_t sourceKey = 0;  // who emitted it (contact point key, joint id): for warm starts
  RowVector warmStart;          // k: previous impulse for this source, or empty

  [[nodiscard]] int rows() const { return static_cast<int>(jacobianA.rows()); }
};

}  // namespace coulomb::joints
