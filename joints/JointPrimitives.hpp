#pragma once
// The three kinds of position constraint every joint is built from, each with its exact
// Jacobian in body twist coordinates (RowBlock.hpp). Derivation (survey: Bender, Erleben,
// Trinkle 2014, sec. 2.1.3 and 4.4.1; the same rows as ODE's and Bullet's joints): a point fixed
// on body X is p = x_X + r with r = R_X a, and moves as dp = dx_X + dtheta_X x r; a direction
// fixed on X moves as du = dtheta_X x u. Hence, with d = p_B - p_A:
//   point     C = p_B - p_A          J_A = [-I, [r_A]x],           J_B = [I, -[r_B]x]
//   dot       C = u_A . v_B          J_A = [0, (u_A x v_B)^T],     J_B = [0, -(u_A x v_B)^T]
//   along     C = t_A . (p_B - p_A)  J_A = [-t_A^T, (t_A x (d + r_A))^T], J_B = [t_A^T, (r_B x
//   t_A)^T]
// ("dot" keeps two directions perpendicular; "along" measures the anchor offset along a
// direction of A, both terms of dC kept so the Jacobian is exact away from C = 0 too.)
#include <coulomb/geometry/Pose.hpp>
#include <coulomb/joints/JointDef.hpp>
#include <coulomb/joints/RowBlock.hpp>

namespace coulomb::joints {

/// A joint frame carried to world by the body's COM pose.
struct WorldFrame {
  Eigen::Vector3d anchor;  // p, world
  Eigen::Vector3d arm;     // r = p - COM
  Eigen::Vector3d axis;
  Eigen::Vector3d normal;
  Eigen::Vector3d binormal;
};

WorldFrame toWorld(const JointFrame& frame, const geometry::Pose& comPose);

/// C(x) and dC/dx of k rows (k <= 6).
struct ConstraintEval {
  RowVector error;        // C: [m] for point/along rows, [-] (~rad) for dot rows
  RowJacobian jacobianA;  // k x 6
  RowJacobian jacobianB;  // k x 6
  explicit ConstraintEval(int rows = 0)
      : error(RowVector::Zero(rows)),
        jacobianA(RowJacobian::Zero(rows, 6)),
        jacobianB(RowJacobian::Zero(rows, 6)) {}
  [[nodiscard]] int rows() const { return static_cast<int>(error.size()); }
};

/// Rows first .. first+2: the anchors coincide.
void setPointRows(ConstraintEval& out, int first, const WorldFrame& a, const WorldFrame& b);
/// Row `row`: u_A . v_B = 0.
void setDotRow(ConstraintEval& out, int row, const Eigen::Vector3d& uA, const Eigen::Vector3d& vB);
/// Row `row`: t_A . (p_B - p_A) = 0 (or the value of that coordinate).
void setAlongRow(ConstraintEval& out, int row, const Eigen::Vector3d& tA, const WorldFrame& a,
                 const WorldFrame& b);
/// Rows first .. first+2: the frames' orientations coincide (a.axis.b.normal, a.normal.b.binormal,
/// a.binormal.b.axis; their Jacobians at C = 0 are the three frame axes, so independent).
void setOrientationRows(ConstraintEval& out, int first, const WorldFrame& a, const WorldFrame& b);

}  // namespace coulomb::joints

namespace coulomb::joints {

/// A joint's scalar coordinate (hinge angle [rad], slider displacement [m]) and its rate row:
/// d(value)/dt = jacobianA t_A + jacobianB t_B (exact where the joint's equality rows hold).
struct JointCoordinate {
  double value = 0.0;
  Eigen::Matrix<double, 1, 6> jacobianA = Eigen::Matrix<double, 1, 6>::Zero();
  Eigen::Matrix<double, 1, 6> jacobianB = Eigen::Matrix<double, 1, 6>::Zero();
};

}  // namespace coulomb::joints
