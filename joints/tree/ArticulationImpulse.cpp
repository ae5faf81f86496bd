#include <coulomb/joints/tree/ArticulationImpulse.hpp>

#include <Eigen/Cholesky>
#include <sstream>
#include <stdexcept>

namespace coulomb::joints::tree {

using geometry::Matrix6d;
using geometry::Vector6d;

ArticulationImpulse::ArticulationImpulse(const Articulation& articulation,
                                         const Eigen::VectorXd& q) {
  reset(articulation, q);
}

void ArticulationImpulse::reset(const Articulation& articulation, const Eigen::VectorXd& q) {
  articulation_ = &articulation;
  forwardKinematics(articulation, q, kinematics_);
  const int n = articulation.linkCount();
  const auto size = static_cast<size_t>(n);
  u_.resize(size);
  dInverse_.resize(size);
  std::vector<Matrix6d>& inertiaA = inertiaA_;
  inertiaA.resize(size);
  for (int i = 0; i < n; ++i) inertiaA[static_cast<size_t>(i)] = articulation.spatialInertia(i);
  // ABA pass 2 (Table 7.1) restricted to the inertias: I^a = I^A - U D^-1 U^T, I^A_p += X^T I^a X.
  for (int i = n - 1; i >= 0; --i) {
    const auto k = static_cast<size_t>(i);
    const MotionSubspace& s = articulation.motionSubspace(i);
    Matrix6d childInertia = inertiaA[k];
    if (s.cols() > 0) {
      u_[k] = inertiaA[k] * s;
      JointMatrix d = s.transpose() * u_[k];
      d.diagonal().array() += articulation.link(i).joint.armature;
      const Eigen::LLT<JointMatrix> llt(d);
      if (llt.info() != Eigen::Success || !(d.diagonal().minCoeff() > 0.0))
        throw std::domain_error("articulation: joint '" + articulation.link(i).joint.name +
                                "' of link '" + articulation.link(i).name +
                                "' moves a subtree with no inertia along its motion");
      dInverse_[k] = llt.solve(JointMatrix::Identity(d.rows(), d.cols()));
      childInertia -= u_[k] * dInverse_[k] * u_[k].transpose();
    }
    const int p = articulation.parent(i);
    if (p >= 0)
      inertiaA[static_cast<size_t>(p)] +=
          kinematics_.parentToLink[k].transformInertiaToParent(childInertia);
  }
}

Eigen::VectorXd ArticulationImpulse::velocityChange(std::span<const Vector6d> linkImpulses,
                                                    const Eigen::VectorXd& jointImpulse) const {
  const int n = articulation_->linkCount();
  if (!linkImpulses.empty() && static_cast<int>(linkImpulses.size()) != n)
    throw std::invalid_argument(
        "articulation impulse: link impulses must be empty or one per link");
  if (jointImpulse.size() != 0) articulation_->checkVelocity(jointImpulse, "joint impulse");
  Eigen::VectorXd dqd;
  sweep(linkImpulses, jointImpulse, dqd);
  return dqd;
}

void ArticulationImpulse::sweep(std::span<const Vector6d> linkImpulses,
                                const Eigen::VectorXd& jointImpulse, Eigen::VectorXd& dqd) const {
  const int n = articulation_->linkCount();
  const auto size = static_cast<size_t>(n);
  // Bias sweep: p^A_i = -impulse_i, u_i = tau_i - S^T p^A_i, p^a = p^A + U D^-1 u (c = 0).
  std::vector<Vector6d>& bias = bias_;
  std::vector<JointVector>& uForce = uForce_;
  bias.resize(size);
  uForce.resize(size);
  for (int i = 0; i < n; ++i)
    bias[static_cast<size_t>(i)] =
        linkImpulses.empty() ? Vector6d::Zero() : Vector6d(-linkImpulses[static_cast<size_t>(i)]);
  for (int i = n - 1; i >= 0; --i) {
    const auto k = static_cast<size_t>(i);
    const MotionSubspace& s = articulation_->motionSubspace(i);
    Vector6d childBias = bias[k];
    if (s.cols() > 0) {
      uForce[k] = -s.transpose() * bias[k];
      if (jointImpulse.size() != 0)
        uForce[k] += jointImpulse.segment(articulation_->vIndex(i), s.cols());
      childBias += u_[k] * (dInverse_[k] * uForce[k]);
    }
    const int p = articulation_->parent(i);
    if (p >= 0)
      bias[static_cast<size_t>(p)] += kinematics_.parentToLink[k].applyTransposeForce(childBias);
  }
  // Acceleration sweep with a_0 = 0: dqd_i = D^-1 (u_i - U^T X a_p), a_i = X a_p + S dqd_i.
  std::vector<Vector6d>& change = change_;
  change.resize(size);
  dqd.resize(articulation_->nv());
  for (int i = 0; i < n; ++i) {
    const auto k = static_cast<size_t>(i);
    const int p = articulation_->parent(i);
    change[k] = p < 0 ? Vector6d::Zero()
                      : kinematics_.parentToLink[k].applyMotion(change[static_cast<size_t>(p)]);
    const MotionSubspace& s = articulation_->motionSubspace(i);
    if (s.cols() == 0) continue;
    const JointVector dqdi = dInverse_[k] * (uForce[k] - u_[k].transpose() * change[k]);
    dqd.segment(articulation_->vIndex(i), s.cols()) = dqdi;
    change[k] += s * dqdi;
  }
}

Eigen::VectorXd ArticulationImpulse::applyInverseMass(const Eigen::VectorXd& jointImpulse) const {
  articulation_->checkVelocity(jointImpulse, "joint impulse");
  return velocityChange({}, jointImpulse);
}

void ArticulationImpulse::applyInverseMass(const Eigen::VectorXd& jointImpulse,
                                           Eigen::VectorXd& dqd) const {
  articulation_->checkVelocity(jointImpulse, "joint impulse");
  sweep({}, jointImpulse, dqd);
}

Eigen::VectorXd ArticulationImpulse::responseToPointImpulse(
    int link, const Eigen::Vector3d& worldPoint, const Eigen::Vector3d& worldImpulse) const {
  checkRows(std::vector<PointImpulseRow>{{link, worldPoint, worldImpulse}});
  std::vector<Vector6d> impulses(static_cast<size_t>(articulation_->linkCount()), Vector6d::Zero());
  impulses[static_cast<size_t>(link)] =
      linkWrenchFromPointForce(kinematics_, link, worldPoint, worldImpulse);
  return velocityChange(impulses, {});
}

void ArticulationImpulse::checkRows(std::span<const PointImpulseRow> rows) const {
  for (size_t r = 0; r < rows.size(); ++r) {
    const PointImpulseRow& row = rows[r];
    std::ostringstream out;
    if (row.link < 0 || row.link >= articulation_->linkCount())
      out << "articulation impulse: row " << r << " names link " << row.link
          << ", out of range [0, " << articulation_->linkCount() << ")";
    else if (!row.point.allFinite() || !row.direction.allFinite())
      out << "articulation impulse: row " << r << " on link '" << articulation_->link(row.link).name
          << "' has a non-finite point or direction";
    else
      continue;
    throw std::invalid_argument(out.str());
  }
}

std::vector<Vector6d> ArticulationImpulse::linkImpulsesOf(std::span<const PointImpulseRow> rows,
                                                          const Eigen::VectorXd& x) const {
  std::vector<Vector6d> impulses(static_cast<size_t>(articulation_->linkCount()), Vector6d::Zero());
  for (size_t r = 0; r < rows.size(); ++r)
    impulses[static_cast<size_t>(rows[r].link)] +=
        linkWrenchFromPointForce(kinematics_, rows[r].link, rows[r].point,
                                 x(static_cast<Eigen::Index>(r)) * rows[r].direction);
  return impulses;
}

Eigen::MatrixXd ArticulationImpulse::rowJacobian(std::span<const PointImpulseRow> rows) const {
  checkRows(rows);
  Eigen::MatrixXd jacobian(static_cast<Eigen::Index>(rows.size()), articulation_->nv());
  for (size_t r = 0; r < rows.size(); ++r)
    jacobian.row(static_cast<Eigen::Index>(r)) =
        rows[r].direction.transpose() *
        pointJacobian(*articulation_, kinematics_, rows[r].link, rows[r].point);
  return jacobian;
}

Eigen::VectorXd ArticulationImpulse::rowVelocities(std::span<const PointImpulseRow> rows,
                                                   const Eigen::VectorXd& qd) const {
  checkRows(rows);
  const std::vector<Vector6d> v = linkVelocities(*articulation_, kinematics_, qd);
  Eigen::VectorXd velocities(static_cast<Eigen::Index>(rows.size()));
  for (size_t r = 0; r < rows.size(); ++r) {
    const geometry::Pose& pose = kinematics_.worldPoses[static_cast<size_t>(rows[r].link)];
    const Vector6d& vi = v[static_cast<size_t>(rows[r].link)];
    const Eigen::Vector3d omega = pose.rotation * vi.head<3>();
    const Eigen::Vector3d pointVelocity =
        pose.rotation * vi.tail<3>() + omega.cross(rows[r].point - pose.position);
    velocities(static_cast<Eigen::Index>(r)) = rows[r].direction.dot(pointVelocity);
  }
  return velocities;
}

Eigen::VectorXd ArticulationImpulse::delassusColumn(std::span<const PointImpulseRow> rows,
                                                    int column) const {
  checkRows(rows);
  if (column < 0 || column >= static_cast<int>(rows.size()))
    throw std::invalid_argument("articulation impulse: Delassus column out of range");
  Eigen::VectorXd unit = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(rows.size()));
  unit(column) = 1.0;
  return applyDelassus(rows, unit);
}

Eigen::MatrixXd ArticulationImpulse::delassus(std::span<const PointImpulseRow> rows) const {
  const auto m = static_cast<Eigen::Index>(rows.size());
  const Eigen::MatrixXd jacobian = rowJacobian(rows);
  Eigen::MatrixXd response(articulation_->nv(), m);  // M^-1 J^T, one impulse pass per column
  for (Eigen::Index s = 0; s < m; ++s) {
    const PointImpulseRow& row = rows[static_cast<size_t>(s)];
    response.col(s) = responseToPointImpulse(row.link, row.point, row.direction);
  }
  Eigen::MatrixXd w = jacobian * response;
  return 0.5 * (w + w.transpose());  // symmetric to round-off; make it exact
}

Eigen::VectorXd ArticulationImpulse::applyDelassus(std::span<const PointImpulseRow> rows,
                                                   const Eigen::VectorXd& x) const {
  checkRows(rows);
  if (x.size() != static_cast<Eigen::Index>(rows.size()) || !x.allFinite())
    throw std::invalid_argument("articulation impulse: x must be finite with one value per row");
  return rowVelocities(rows, velocityChange(linkImpulsesOf(rows, x), {}));
}

}  // namespace coulomb::joints::tree
