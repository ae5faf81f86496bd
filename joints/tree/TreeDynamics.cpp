#include <coulomb/joints/tree/TreeDynamics.hpp>

#include <coulomb/joints/tree/TreeKinematics.hpp>

#include <Eigen/Cholesky>
#include <sstream>
#include <stdexcept>

namespace coulomb::joints::tree {

namespace {
using geometry::Matrix6d;
using geometry::Vector6d;
using ForceColumns = Eigen::Matrix<double, 6, Eigen::Dynamic, 0, 6, 6>;

void checkWrenches(const Articulation& articulation, std::span<const Vector6d> wrenches) {
  if (wrenches.empty()) return;
  if (static_cast<int>(wrenches.size()) != articulation.linkCount()) {
    std::ostringstream out;
    out << "articulation: " << wrenches.size() << " link wrenches given, expected 0 or "
        << articulation.linkCount();
    throw std::invalid_argument(out.str());
  }
  for (int i = 0; i < articulation.linkCount(); ++i)
    if (!wrenches[static_cast<size_t>(i)].allFinite())
      throw std::invalid_argument("articulation: link '" + articulation.link(i).name +
                                  "' has a non-finite external wrench");
}

Vector6d wrenchOf(std::span<const Vector6d> wrenches, int i) {
  return wrenches.empty() ? Vector6d::Zero() : wrenches[static_cast<size_t>(i)];
}

/// D^-1 for the articulated joint inertia D = S^T I^A S + armature (Table 7.1), or a clear
/// error when the subtree behind the joint has no inertia along its motion.
JointMatrix invertJointInertia(const Articulation& articulation, int i, const JointMatrix& d) {
  const Eigen::LLT<JointMatrix> llt(d);
  if (llt.info() != Eigen::Success || !(d.diagonal().minCoeff() > 0.0)) {
    const TreeLink& link = articulation.link(i);
    throw std::domain_error("articulation: joint '" + link.joint.name + "' of link '" + link.name +
                            "' moves a subtree with no inertia along its motion (S^T I^A S is "
                            "singular): give the links mass or the joint armature");
  }
  return llt.solve(JointMatrix::Identity(d.rows(), d.cols()));
}
}  // namespace

Eigen::VectorXd forwardDynamics(const Articulation& articulation, const Eigen::VectorXd& q,
                                const Eigen::VectorXd& qd, const Eigen::VectorXd& tau,
                                std::span<const Vector6d> linkWrenches) {
  AbaWorkspace work;
  Eigen::VectorXd qdd;
  forwardDynamics(articulation, q, qd, tau, linkWrenches, work, qdd);
  return qdd;
}

void forwardDynamics(const Articulation& articulation, const Eigen::VectorXd& q,
                     const Eigen::VectorXd& qd, const Eigen::VectorXd& tau,
                     std::span<const Vector6d> linkWrenches, AbaWorkspace& work,
                     Eigen::VectorXd& qdd) {
  articulation.checkVelocity(qd, "qd");
  articulation.checkVelocity(tau, "tau");
  checkWrenches(articulation, linkWrenches);
  forwardKinematics(articulation, q, work.kinematics);
  const TreeKinematics& kin = work.kinematics;
  const int n = articulation.linkCount();
  const auto size = static_cast<size_t>(n);
  for (auto* links : {&work.v, &work.c, &work.pA, &work.a}) links->resize(size);
  work.inertiaA.resize(size);
  work.u.resize(size);
  work.dInverse.resize(size);
  work.uForce.resize(size);
  std::vector<Vector6d>&v = work.v, &c = work.c, &pA = work.pA, &a = work.a;
  std::vector<Matrix6d>& inertiaA = work.inertiaA;
  std::vector<ForceColumns>& u = work.u;
  std::vector<JointMatrix>& dInverse = work.dInverse;
  std::vector<JointVector>& uForce = work.uForce;

  // Pass 1 (root to leaves): velocities, velocity-product accelerations c_i = v_i x v_J (c_J = 0
  // for our joints), rigid-body inertias and bias forces p_i = v_i x* I_i v_i - f_ext.
  for (int i = 0; i < n; ++i) {
    const auto k = static_cast<size_t>(i);
    const MotionSubspace& s = articulation.motionSubspace(i);
    const Vector6d vJ = s * qd.segment(articulation.vIndex(i), s.cols());
    const int p = articulation.parent(i);
    v[k] = (p < 0 ? Vector6d::Zero() : kin.parentToLink[k].applyMotion(v[static_cast<size_t>(p)])) +
           vJ;
    c[k] = geometry::crossMotion(v[k], vJ);
    inertiaA[k] = articulation.spatialInertia(i);
    pA[k] = geometry::crossForce(v[k], inertiaA[k] * v[k]) - wrenchOf(linkWrenches, i);
  }
  // Pass 2 (leaves to root): articulated-body inertias and bias forces.
  for (int i = n - 1; i >= 0; --i) {
    const auto k = static_cast<size_t>(i);
    const TreeJoint& joint = articulation.link(i).joint;
    const MotionSubspace& s = articulation.motionSubspace(i);
    const int dofs = static_cast<int>(s.cols());
    Matrix6d childInertia = inertiaA[k];
    Vector6d childBias = pA[k];
    if (dofs > 0) {
      const auto qdi = qd.segment(articulation.vIndex(i), dofs);
      u[k] = inertiaA[k] * s;  // U_i = I^A_i S_i
      JointMatrix d = s.transpose() * u[k];
      d.diagonal().array() += joint.armature;
      dInverse[k] = invertJointInertia(articulation, i, d);
      // u_i = tau_i - S_i^T p^A_i (the product first: in one expression with the segments of
      // tau and qd, Eigen would evaluate it into a heap temporary)
      uForce[k].noalias() = s.transpose() * pA[k];
      uForce[k] = tau.segment(articulation.vIndex(i), dofs) - joint.damping * qdi - uForce[k];
      childInertia -= u[k] * dInverse[k] * u[k].transpose();
      childBias += u[k] * (dInverse[k] * uForce[k]);
    }
    childBias += childInertia * c[k];  // p^a = p^A + I^a c + U D^-1 u
    const int p = articulation.parent(i);
    if (p < 0) continue;
    inertiaA[static_cast<size_t>(p)] += kin.parentToLink[k].transformInertiaToParent(childInertia);
    pA[static_cast<size_t>(p)] += kin.parentToLink[k].applyTransposeForce(childBias);
  }
  // Pass 3 (root to leaves): accelerations, with a_0 = -g.
  const Vector6d baseAcceleration =
      geometry::motionVector(Eigen::Vector3d::Zero(), -articulation.gravity());
  qdd.resize(articulation.nv());
  for (int i = 0; i < n; ++i) {
    const auto k = static_cast<size_t>(i);
    const int p = articulation.parent(i);
    const Vector6d aParent =
        kin.parentToLink[k].applyMotion(p < 0 ? baseAcceleration : a[static_cast<size_t>(p)]) +
        c[k];
    const MotionSubspace& s = articulation.motionSubspace(i);
    a[k] = aParent;
    if (s.cols() == 0) continue;
    const JointVector qddi = dInverse[k] * (uForce[k] - u[k].transpose() * aParent);
    qdd.segment(articulation.vIndex(i), s.cols()) = qddi;
    a[k] += s * qddi;
  }
}

Eigen::VectorXd inverseDynamics(const Articulation& articulation, const Eigen::VectorXd& q,
                                const Eigen::VectorXd& qd, const Eigen::VectorXd& qdd,
                                std::span<const Vector6d> linkWrenches) {
  articulation.checkVelocity(qd, "qd");
  articulation.checkVelocity(qdd, "qdd");
  checkWrenches(articulation, linkWrenches);
  const TreeKinematics kin = forwardKinematics(articulation, q);
  const int n = articulation.linkCount();
  const auto size = static_cast<size_t>(n);
  std::vector<Vector6d> v(size), a(size), f(size);
  const Vector6d baseAcceleration =
      geometry::motionVector(Eigen::Vector3d::Zero(), -articulation.gravity());
  // Forward pass (Table 5.1): v_i = X v_p + S qd, a_i = X a_p + S qdd + v_i x S qd,
  // f_i = I a_i + v_i x* I v_i - f_ext.
  for (int i = 0; i < n; ++i) {
    const auto k = static_cast<size_t>(i);
    const MotionSubspace& s = articulation.motionSubspace(i);
    const Vector6d vJ = s * qd.segment(articulation.vIndex(i), s.cols());
    const int p = articulation.parent(i);
    const PluckerTransform& x = kin.parentToLink[k];
    v[k] = (p < 0 ? Vector6d::Zero() : x.applyMotion(v[static_cast<size_t>(p)])) + vJ;
    a[k] = x.applyMotion(p < 0 ? baseAcceleration : a[static_cast<size_t>(p)]) +
           s * qdd.segment(articulation.vIndex(i), s.cols()) + geometry::crossMotion(v[k], vJ);
    const Matrix6d& inertia = articulation.spatialInertia(i);
    f[k] = inertia * a[k] + geometry::crossForce(v[k], inertia * v[k]) - wrenchOf(linkWrenches, i);
  }
  // Backward pass: tau_i = S^T f_i (+ armature qdd + damping qd), f_p += X^T f_i.
  Eigen::VectorXd tau(articulation.nv());
  for (int i = n - 1; i >= 0; --i) {
    const auto k = static_cast<size_t>(i);
    const TreeJoint& joint = articulation.link(i).joint;
    const MotionSubspace& s = articulation.motionSubspace(i);
    const int index = articulation.vIndex(i);
    const auto dofs = s.cols();
    tau.segment(index, dofs) = s.transpose() * f[k] + joint.armature * qdd.segment(index, dofs) +
                               joint.damping * qd.segment(index, dofs);
    const int p = articulation.parent(i);
    if (p >= 0) f[static_cast<size_t>(p)] += kin.parentToLink[k].applyTransposeForce(f[k]);
  }
  return tau;
}

Eigen::VectorXd biasForces(const Articulation& articulation, const Eigen::VectorXd& q,
                           const Eigen::VectorXd& qd) {
  return inverseDynamics(articulation, q, qd, Eigen::VectorXd::Zero(articulation.nv()));
}

Eigen::MatrixXd massMatrix(const Articulation& articulation, const Eigen::VectorXd& q) {
  const TreeKinematics kin = forwardKinematics(articulation, q);
  const int n = articulation.linkCount();
  // Composite inertias I^c_i = I_i + sum over children X^T I^c X (Table 6.2).
  std::vector<Matrix6d> composite(static_cast<size_t>(n));
  for (int i = 0; i < n; ++i) composite[static_cast<size_t>(i)] = articulation.spatialInertia(i);
  for (int i = n - 1; i >= 0; --i) {
    const int p = articulation.parent(i);
    if (p >= 0)
      composite[static_cast<size_t>(p)] +=
          kin.parentToLink[static_cast<size_t>(i)].transformInertiaToParent(
              composite[static_cast<size_t>(i)]);
  }
  Eigen::MatrixXd mass = Eigen::MatrixXd::Zero(articulation.nv(), articulation.nv());
  for (int i = 0; i < n; ++i) {
    const MotionSubspace& s = articulation.motionSubspace(i);
    const auto dofs = s.cols();
    if (dofs == 0) continue;
    const int row = articulation.vIndex(i);
    ForceColumns force = composite[static_cast<size_t>(i)] * s;  // F = I^c_i S_i
    mass.block(row, row, dofs, dofs) = s.transpose() * force;
    mass.block(row, row, dofs, dofs).diagonal().array() += articulation.link(i).joint.armature;
    // Walk to the root: F = X_j^T F, M_{lambda(j), i} = S^T F (and the symmetric block).
    for (int j = i; articulation.parent(j) >= 0;) {
      force = kin.parentToLink[static_cast<size_t>(j)].applyTransposeForces(force);
      j = articulation.parent(j);
      const MotionSubspace& sj = articulation.motionSubspace(j);
      if (sj.cols() == 0) continue;
      const int column = articulation.vIndex(j);
      mass.block(column, row, sj.cols(), dofs) = sj.transpose() * force;
      mass.block(row, column, dofs, sj.cols()) =
          mass.block(column, row, sj.cols(), dofs).transpose();
    }
  }
  return mass;
}

}  // namespace coulomb::joints::tree
