#include <coulomb/joints/tree/TreeKinematics.hpp>

#include <sstream>
#include <stdexcept>

namespace coulomb::joints::tree {

namespace {
void checkLink(const Articulation& articulation, int link) {
  if (link < 0 || link >= articulation.linkCount()) {
    std::ostringstream out;
    out << "articulation: link index " << link << " out of range [0, " << articulation.linkCount()
        << ")";
    throw std::invalid_argument(out.str());
  }
}
}  // namespace

TreeKinematics forwardKinematics(const Articulation& articulation, const Eigen::VectorXd& q) {
  TreeKinematics kin;
  forwardKinematics(articulation, q, kin);
  return kin;
}

void forwardKinematics(const Articulation& articulation, const Eigen::VectorXd& q,
                       TreeKinematics& kin) {
  articulation.checkConfiguration(q);
  const auto n = static_cast<size_t>(articulation.linkCount());
  kin.parentToLink.resize(n);
  kin.worldPoses.resize(n);
  for (int i = 0; i < articulation.linkCount(); ++i) {
    const TreeJoint& joint = articulation.link(i).joint;
    // Link frame in the parent frame: X_T (joint placement) then X_J(q) (Featherstone eq. 4.34).
    const geometry::Pose linkInParent =
        joint.parentToJoint * joint.jointMotion(q.data() + articulation.qIndex(i));
    const auto k = static_cast<size_t>(i);
    kin.parentToLink[k] = PluckerTransform::fromPose(linkInParent);
    const int p = articulation.parent(i);
    kin.worldPoses[k] =
        p < 0 ? linkInParent : kin.worldPoses[static_cast<size_t>(p)] * linkInParent;
    kin.worldPoses[k].rotation.normalize();
  }
}

std::vector<geometry::Vector6d> linkVelocities(const Articulation& articulation,
                                               const TreeKinematics& kinematics,
                                               const Eigen::VectorXd& qd) {
  std::vector<geometry::Vector6d> v;
  linkVelocities(articulation, kinematics, qd, v);
  return v;
}

void linkVelocities(const Articulation& articulation, const TreeKinematics& kinematics,
                    const Eigen::VectorXd& qd, std::vector<geometry::Vector6d>& v) {
  articulation.checkVelocity(qd);
  v.resize(static_cast<size_t>(articulation.linkCount()));
  for (int i = 0; i < articulation.linkCount(); ++i) {
    const int p = articulation.parent(i);
    const auto k = static_cast<size_t>(i);
    const MotionSubspace& s = articulation.motionSubspace(i);
    // v_i = X_i v_parent + S_i qd_i (Featherstone eq. 4.32 / Table 5.1).
    v[k] = p < 0 ? geometry::Vector6d::Zero()
                 : kinematics.parentToLink[k].applyMotion(v[static_cast<size_t>(p)]);
    if (s.cols() > 0) v[k] += s * qd.segment(articulation.vIndex(i), s.cols());
  }
}

Eigen::Vector3d pointVelocity(const Articulation& articulation, const TreeKinematics& kinematics,
                              const Eigen::VectorXd& qd, int link,
                              const Eigen::Vector3d& worldPoint) {
  checkLink(articulation, link);
  return pointJacobian(articulation, kinematics, link, worldPoint) * qd;
}

Eigen::Matrix<double, 6, Eigen::Dynamic> twistJacobian(const Articulation& articulation,
                                                       const TreeKinematics& kinematics, int link,
                                                       const Eigen::Vector3d& worldPoint) {
  Eigen::Matrix<double, 6, Eigen::Dynamic> jacobian;
  twistJacobian(articulation, kinematics, link, worldPoint, jacobian);
  return jacobian;
}

void twistJacobian(const Articulation& articulation, const TreeKinematics& kinematics, int link,
                   const Eigen::Vector3d& worldPoint,
                   Eigen::Matrix<double, 6, Eigen::Dynamic>& jacobian) {
  checkLink(articulation, link);
  jacobian.setZero(6, articulation.nv());
  // Walk from the link to the root: each joint's motion subspace, moved to world coordinates,
  // gives its columns (Featherstone sec. 4.4): omega = R s_w, v_point = R s_v + omega x (p - o).
  for (int j = link; j >= 0; j = articulation.parent(j)) {
    const MotionSubspace& s = articulation.motionSubspace(j);
    const geometry::Pose& pose = kinematics.worldPoses[static_cast<size_t>(j)];
    const Eigen::Matrix3d r = pose.rotationMatrix();
    const Eigen::Vector3d lever = worldPoint - pose.position;
    for (Eigen::Index c = 0; c < s.cols(); ++c) {
      const Eigen::Vector3d omega = r * s.col(c).head<3>();
      const Eigen::Index column = articulation.vIndex(j) + c;
      jacobian.col(column).head<3>() = r * s.col(c).tail<3>() + omega.cross(lever);
      jacobian.col(column).tail<3>() = omega;
    }
  }
}

Eigen::Matrix<double, 3, Eigen::Dynamic> pointJacobian(const Articulation& articulation,
                                                       const TreeKinematics& kinematics, int link,
                                                       const Eigen::Vector3d& worldPoint) {
  return twistJacobian(articulation, kinematics, link, worldPoint).topRows<3>();
}

geometry::Vector6d linkWrenchFromPointForce(const TreeKinematics& kinematics, int link,
                                            const Eigen::Vector3d& worldPoint,
                                            const Eigen::Vector3d& worldForce) {
  const geometry::Pose& pose = kinematics.worldPoses.at(static_cast<size_t>(link));
  const Eigen::Vector3d localPoint = pose.applyInverse(worldPoint);
  const Eigen::Vector3d localForce = pose.rotation.conjugate() * worldForce;
  return geometry::motionVector(localPoint.cross(localForce), localForce);
}

double kineticEnergy(const Articulation& articulation, const TreeKinematics& kinematics,
                     const Eigen::VectorXd& qd) {
  const std::vector<geometry::Vector6d> v = linkVelocities(articulation, kinematics, qd);
  double energy = 0.0;
  for (int i = 0; i < articulation.linkCount(); ++i) {
    const geometry::Vector6d& vi = v[static_cast<size_t>(i)];
    energy += 0.5 * vi.dot(articulation.spatialInertia(i) * vi);
    const auto qdi = qd.segment(articulation.vIndex(i), articulation.link(i).joint.nv());
    energy += 0.5 * articulation.link(i).joint.armature * qdi.squaredNorm();
  }
  return energy;
}

double potentialEnergy(const Articulation& articulation, const TreeKinematics& kinematics) {
  double energy = 0.0;
  for (int i = 0; i < articulation.linkCount(); ++i) {
    const geometry::SpatialInertia& inertia = articulation.link(i).inertia;
    const Eigen::Vector3d com =
        kinematics.worldPoses[static_cast<size_t>(i)].apply(inertia.centerOfMass);
    energy -= inertia.mass * articulation.gravity().dot(com);
  }
  return energy;
}

geometry::Vector6d spatialMomentum(const Articulation& articulation,
                                   const TreeKinematics& kinematics, const Eigen::VectorXd& qd) {
  const std::vector<geometry::Vector6d> v = linkVelocities(articulation, kinematics, qd);
  Eigen::Vector3d linear = Eigen::Vector3d::Zero(), angular = Eigen::Vector3d::Zero();
  for (int i = 0; i < articulation.linkCount(); ++i) {
    // h_i = I_i v_i in link coordinates (torque-like part about the link origin; force part).
    const geometry::Vector6d h = articulation.spatialInertia(i) * v[static_cast<size_t>(i)];
    const geometry::Pose& pose = kinematics.worldPoses[static_cast<size_t>(i)];
    const Eigen::Vector3d p = pose.rotation * h.tail<3>();
    linear += p;
    angular += pose.rotation * h.head<3>() + pose.position.cross(p);
  }
  geometry::Vector6d result;
  result << linear, angular;
  return result;
}

}  // namespace coulomb::joints::tree
