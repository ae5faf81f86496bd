#pragma once
// Dynamics of an Articulation in joint space:  M(q) qdd + h(q, qd) = tau + J^T f_ext,
// with h = C(q, qd) qd + g(q) + damping * qd and M including each joint's armature on its
// diagonal. Three classic algorithms (Featherstone, "Rigid Body Dynamics Algorithms", 2008):
//   forwardDynamics   articulated-body algorithm, O(n)           ch. 7, Table 7.1
//   inverseDynamics   recursive Newton-Euler algorithm, O(n)      ch. 5, Table 5.1
//   massMatrix        composite-rigid-body algorithm             ch. 6, Table 6.2
// Gravity enters as a fictitious base acceleration a_0 = -g (sec. 5.3). External wrenches are
// one spatial force per link in link coordinates (torque about the link origin; force), see
// linkWrenchFromPointForce; an empty span means none. Inputs are checked (sizes, finiteness):
// std::invalid_argument names the link/joint; a joint whose subtree has no inertia along its
// motion (S^T I^A S singular) throws std::domain_error naming the joint instead of a NaN.
#include <coulomb/joints/tree/Articulation.hpp>
#include <coulomb/joints/tree/TreeKinematics.hpp>

#include <span>
#include <vector>

namespace coulomb::joints::tree {

/// qdd (nv) by the articulated-body algorithm.
Eigen::VectorXd forwardDynamics(const Articulation& articulation, const Eigen::VectorXd& q,
                                const Eigen::VectorXd& qd, const Eigen::VectorXd& tau,
                                std::span<const geometry::Vector6d> linkWrenches = {});

/// The per-link values of the articulated-body algorithm, kept by a caller that runs it every
/// step so that it allocates nothing once sized. One workspace is not for two calls at once.
struct AbaWorkspace {
  TreeKinematics kinematics;
  std::vector<geometry::Vector6d> v, c, pA, a;
  std::vector<geometry::Matrix6d> inertiaA;
  std::vector<Eigen::Matrix<double, 6, Eigen::Dynamic, 0, 6, 6>> u;  // U_i = I^A_i S_i
  std::vector<JointMatrix> dInverse;
  std::vector<JointVector> uForce;
};

/// The same into `qdd`, the per-link values in `work`.
void forwardDynamics(const Articulation& articulation, const Eigen::VectorXd& q,
                     const Eigen::VectorXd& qd, const Eigen::VectorXd& tau,
                     std::span<const geometry::Vector6d> linkWrenches, AbaWorkspace& work,
                     Eigen::VectorXd& qdd);

/// tau (nv) that produces qdd, by the recursive Newton-Euler algorithm.
Eigen::VectorXd inverseDynamics(const Articulation& articulation, const Eigen::VectorXd& q,
                                const Eigen::VectorXd& qd, const Eigen::VectorXd& qdd,
                                std::span<const geometry::Vector6d> linkWrenches = {});

/// h(q, qd) = inverseDynamics(q, qd, 0): Coriolis, centrifugal, gravity and damping forces.
Eigen::VectorXd biasForces(const Articulation& articulation, const Eigen::VectorXd& q,
                           const Eigen::VectorXd& qd);

/// The joint-space inertia matrix M(q) (nv x nv, symmetric positive definite), by CRBA.
Eigen::MatrixXd massMatrix(const Articulation& articulation, const Eigen::VectorXd& q);

}  // namespace coulomb::joints::tree
