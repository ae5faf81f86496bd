#pragma once
// Velocity response of an articulation to impulses: the tree's part of the Delassus operator
// W = J M^-1 J^T for contact and limit rows on its links.
//
// "Impulse-level ABA": the articulated-body algorithm (Featherstone 2008, Table 7.1) with zero
// velocity and zero gravity, the impulses as the external forces and dqd in place of qdd. The
// articulated inertias I^A, U = I^A S and D^-1 depend on q alone, so they are computed once here
// (constructor, O(n)) and every response is then two O(n) sweeps (bias up, accelerations down):
//   velocityChange(...)  = M^-1 (jointImpulse + sum_links J_link^T linkImpulse)
// exactly, without forming M. Damping does not act on impulses (it is a force, O(h)).
// The object holds a reference to the Articulation: keep the model alive while using it.
#include <coulomb/joints/tree/Articulation.hpp>
#include <coulomb/joints/tree/TreeKinematics.hpp>

#include <span>
#include <vector>

namespace coulomb::joints::tree {

/// One scalar row on a link: the velocity of the world point `point` (moving with link `link`)
/// along the world direction `direction`; its impulse lambda acts as the world impulse
/// lambda * direction at that point.
struct PointImpulseRow {
  int link = 0;
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  Eigen::Vector3d direction = Eigen::Vector3d::UnitZ();
};

class ArticulationImpulse {
 public:
  /// Articulated inertias at q (checks q; std::domain_error if a joint's D is singular).
  ArticulationImpulse(const Articulation& articulation, const Eigen::VectorXd& q);
  /// Empty: reset() before any other use.
  ArticulationImpulse() = default;
  /// The same as constructing anew, reusing this object's storage (the step's form: no
  /// allocation once sized for the largest articulation it has seen).
  void reset(const Articulation& articulation, const Eigen::VectorXd& q);

  [[nodiscard]] const TreeKinematics& kinematics() const { return kinematics_; }

  /// dqd = M^-1 (jointImpulse + sum J^T linkImpulses): one O(n) pass. linkImpulses: empty or
  /// one spatial impulse per link in link coordinates; jointImpulse: empty or nv values.
  [[nodiscard]] Eigen::VectorXd velocityChange(std::span<const geometry::Vector6d> linkImpulses,
                                               const Eigen::VectorXd& jointImpulse) const;
  /// M^-1 tau in O(n) (joint-space rows such as limits and motors use it).
  [[nodiscard]] Eigen::VectorXd applyInverseMass(const Eigen::VectorXd& jointImpulse) const;
  /// The same into `dqd`, the sweeps in this object's scratch: no allocation once sized (so one
  /// object is not for two threads at once).
  void applyInverseMass(const Eigen::VectorXd& jointImpulse, Eigen::VectorXd& dqd) const;
  /// dqd for the world impulse `worldImpulse` at `worldPoint` on `link`.
  [[nodiscard]] Eigen::VectorXd responseToPointImpulse(int link, const Eigen::Vector3d& worldPoint,
                                                       const Eigen::Vector3d& worldImpulse) const;

  /// The rows' Jacobian, m x nv: row r = direction_r^T pointJacobian(link_r, point_r).
  [[nodiscard]] Eigen::MatrixXd rowJacobian(std::span<const PointImpulseRow> rows) const;
  /// Dense W = J M^-1 J^T (m x m) by m impulse-level ABA passes (one column each).
  [[nodiscard]] Eigen::MatrixXd delassus(std::span<const PointImpulseRow> rows) const;
  /// Column s of W: the rows' velocity change for a unit impulse on row s (one O(n) pass).
  [[nodiscard]] Eigen::VectorXd delassusColumn(std::span<const PointImpulseRow> rows,
                                               int column) const;
  /// W x without forming W: one O(n) pass plus O(1) per row.
  [[nodiscard]] Eigen::VectorXd applyDelassus(std::span<const PointImpulseRow> rows,
                                              const Eigen::VectorXd& x) const;
  /// The rows' velocities J dqd for a joint velocity (change) dqd: O(n + m).
  [[nodiscard]] Eigen::VectorXd rowVelocities(std::span<const PointImpulseRow> rows,
                                              const Eigen::VectorXd& qd) const;

 private:
  using ForceColumns = Eigen::Matrix<double, 6, Eigen::Dynamic, 0, 6, 6>;
  void checkRows(std::span<const PointImpulseRow> rows) const;
  std::vector<geometry::Vector6d> linkImpulsesOf(std::span<const PointImpulseRow> rows,
                                                 const Eigen::VectorXd& x) const;

  const Articulation* articulation_ = nullptr;  // not owned
  TreeKinematics kinematics_;
  std::vector<ForceColumns> u_;        // U_i = I^A_i S_i
  std::vector<JointMatrix> dInverse_;  // D_i^-1 = (S_i^T I^A_i S_i + armature)^-1
  // The sweeps' per-link values, kept for their storage.
  mutable std::vector<geometry::Vector6d> bias_, change_;
  mutable std::vector<JointVector> uForce_;
  std::vector<geometry::Matrix6d> inertiaA_;  // reset()'s articulated inertias
  void sweep(std::span<const geometry::Vector6d> linkImpulses, const Eigen::VectorXd& jointImpulse,
             Eigen::VectorXd& dqd) const;
};

}  // namespace coulomb::joints::tree
