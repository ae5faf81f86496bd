#include <coulomb/integrators/ArticulationIntegrator.hpp>

#include <coulomb/geometry/Quaternion.hpp>
#include <coulomb/joints/tree/TreeDynamics.hpp>

#include <cmath>
#include <stdexcept>

namespace coulomb::integrators {

namespace {
using joints::tree::TreeJointType;

Eigen::Quaterniond readQuaternion(const Eigen::VectorXd& q, int start) {
  return Eigen::Quaterniond(q(start), q(start + 1), q(start + 2), q(start + 3));
}

void writeQuaternion(Eigen::VectorXd& q, int start, Eigen::Quaterniond r) {
  r.normalize();
  q.segment<4>(start) << r.w(), r.x(), r.y(), r.z();
}

/// V(phi) = I + (1 - cos t)/t^2 [phi]x + (t - sin t)/t^3 [phi]x^2, t = |phi|: the SO(3) left
/// Jacobian, so that exp of the twist (phi, h v) translates by R V(phi) h v (Murray, Li, Sastry
/// 1994, eq. 2.36). Taylor series below 1e-4 rad keep it accurate.
Eigen::Matrix3d leftJacobian(const Eigen::Vector3d& phi) {
  const double t = phi.norm();
  const Eigen::Matrix3d k = geometry::skew(phi);
  double a = 0.5 - t * t / 24.0, b = 1.0 / 6.0 - t * t / 120.0;
  if (t > 1e-4) {
    a = (1.0 - std::cos(t)) / (t * t);
    b = (t - std::sin(t)) / (t * t * t);
  }
  return Eigen::Matrix3d::Identity() + a * k + b * k * k;
}
}  // namespace

void integrateConfiguration(const joints::tree::Articulation& articulation, Eigen::VectorXd& q,
                            const Eigen::VectorXd& qd, double h) {
  if (!std::isfinite(h)) throw std::invalid_argument("integrateConfiguration: h is not finite");
  articulation.checkConfiguration(q);
  articulation.checkVelocity(qd, "qd");
  for (int i = 0; i < articulation.linkCount(); ++i) {
    const int iq = articulation.qIndex(i), iv = articulation.vIndex(i);
    switch (articulation.link(i).joint.type) {
      case TreeJointType::Revolute:
      case TreeJointType::Continuous:
      case TreeJointType::Prismatic:
        q(iq) += h * qd(iv);
        break;
      case TreeJointType::Fixed:
        break;
      case TreeJointType::Spherical: {
        const Eigen::Vector3d omega = qd.segment<3>(iv);
        writeQuaternion(q, iq, geometry::integrateBodyRotation(readQuaternion(q, iq), omega, h));
        break;
      }
      case TreeJointType::Floating: {
        const Eigen::Quaterniond r = readQuaternion(q, iq + 3).normalized();
        const Eigen::Vector3d phi = h * qd.segment<3>(iv);
        q.segment<3>(iq) += r * (leftJacobian(phi) * (h * qd.segment<3>(iv + 3)));
        writeQuaternion(q, iq + 3, r * geometry::quaternionExp(phi));
        break;
      }
    }
  }
}

Eigen::VectorXd predictArticulationVelocity(const joints::tree::Articulation& articulation,
                                            const Eigen::VectorXd& q, const Eigen::VectorXd& qd,
                                            const Eigen::VectorXd& tau, double h,
                                            std::span<const geometry::Vector6d> linkWrenches) {
  if (!std::isfinite(h) || h < 0.0)
    throw std::invalid_argument("predictArticulationVelocity: h must be finite and >= 0");
  return qd + h * joints::tree::forwardDynamics(articulation, q, qd, tau, linkWrenches);
}

void predictArticulationVelocity(const joints::tree::Articulation& articulation,
                                 const Eigen::VectorXd& q, Eigen::VectorXd& qd,
                                 const Eigen::VectorXd& tau, double h,
                                 joints::tree::AbaWorkspace& work, Eigen::VectorXd& qdd) {
  if (!std::isfinite(h) || h < 0.0)
    throw std::invalid_argument("predictArticulationVelocity: h must be finite and >= 0");
  joints::tree::forwardDynamics(articulation, q, qd, tau, {}, work, qdd);
  qd += h * qdd;
}

void stepArticulation(const joints::tree::Articulation& articulation, Eigen::VectorXd& q,
                      Eigen::VectorXd& qd, const Eigen::VectorXd& tau, double h,
                      std::span<const geometry::Vector6d> linkWrenches) {
  qd = predictArticulationVelocity(articulation, q, qd, tau, h, linkWrenches);
  integrateConfiguration(articulation, q, qd, h);
}

}  // namespace coulomb::integrators
