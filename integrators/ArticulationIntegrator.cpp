#include <coulomb/integrators/ArticulationIntegrator.hpp>

#include <coulomb/geometry/Quaternion.hpp>
#include <coulomb/joints/tree/TreeDynamics.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
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

namespace {
// Dormand-Prince 5(4): the stage matrix (row 6 is the 5th-order solution, so stage 6's derivative
// starts the next sub-step) and the error weights b - b*.
constexpr double kA[7][6] = {
    {0, 0, 0, 0, 0, 0},
    {1.0 / 5, 0, 0, 0, 0, 0},
    {3.0 / 40, 9.0 / 40, 0, 0, 0, 0},
    {44.0 / 45, -56.0 / 15, 32.0 / 9, 0, 0, 0},
    {19372.0 / 6561, -25360.0 / 2187, 64448.0 / 6561, -212.0 / 729, 0, 0},
    {9017.0 / 3168, -355.0 / 33, 46732.0 / 5247, 49.0 / 176, -5103.0 / 18656, 0},
    {35.0 / 384, 0, 500.0 / 1113, 125.0 / 192, -2187.0 / 6784, 11.0 / 84}};
constexpr double kError[7] = {71.0 / 57600,      0,          -71.0 / 16695, 71.0 / 1920,
                              -17253.0 / 339200, 22.0 / 525, -1.0 / 40};
}  // namespace

void rungeKuttaStep(const joints::tree::Articulation& articulation, Eigen::VectorXd& q,
                    Eigen::VectorXd& qd, const Eigen::VectorXd& tau, double h,
                    joints::tree::AbaWorkspace& aba, TreeStepScratch& s) {
  if (!std::isfinite(h) || h < 0.0)
    throw std::invalid_argument("rungeKuttaStep: h must be finite and >= 0");
  using joints::tree::forwardDynamics;
  auto& kq = s.stageVelocity;
  auto& kv = s.stageAcceleration;
  kq[0] = qd;  // (q, qd) is the sub-step's start until a sub-step is kept
  forwardDynamics(articulation, q, qd, tau, {}, aba, kv[0]);
  s.substeps = 0;
  double left = h, sub = h;
  int attempts = 0;
  while (left > 0.0) {
    if (left < sub * (1.0 + 1e-12)) sub = left;  // land on h exactly
    bool finite = true;  // a stage that left the finite numbers: the sub-step is retried shorter
    for (int i = 1; i < 7 && finite; ++i) {
      s.combination = kA[i][0] * kq[0];
      s.stageQd = kA[i][0] * kv[0];
      for (int j = 1; j < i; ++j) {
        s.combination += kA[i][j] * kq[static_cast<std::size_t>(j)];
        s.stageQd += kA[i][j] * kv[static_cast<std::size_t>(j)];
      }
      s.stageQd = qd + sub * s.stageQd;
      finite = s.combination.allFinite() && s.stageQd.allFinite();
      if (!finite) break;
      s.stageQ = q;
      integrateConfiguration(articulation, s.stageQ, s.combination, sub);
      kq[static_cast<std::size_t>(i)] = s.stageQd;
      forwardDynamics(articulation, s.stageQ, s.stageQd, tau, {}, aba,
                      kv[static_cast<std::size_t>(i)]);
    }
    if (finite) {
      s.errorQ = kError[0] * kq[0];
      s.errorQd = kError[0] * kv[0];
      for (int j = 1; j < 7; ++j) {
        s.errorQ += kError[j] * kq[static_cast<std::size_t>(j)];
        s.errorQd += kError[j] * kv[static_cast<std::size_t>(j)];
      }
    }
    finite = finite && s.errorQ.allFinite() && s.errorQd.allFinite();
    double error = finite ? 0.0 : std::numeric_limits<double>::infinity();
    for (Eigen::Index k = 0; finite && k < qd.size(); ++k) {  // largest error / tolerance
      const double scale = 1.0 + std::max(std::abs(qd(k)), std::abs(s.stageQd(k)));
      error = std::max({error, sub * std::abs(s.errorQ(k)) / kTreeStepTolerance,
                        sub * std::abs(s.errorQd(k)) / (kTreeStepTolerance * scale)});
    }
    ++attempts;
    // Step-size rule of Hairer et al. II.4 (4.13) with safety 0.9 and factors in [0.2, 5].
    const double factor = std::clamp(0.9 * std::pow(std::max(error, 1e-10), -0.2), 0.2, 5.0);
    if (!std::isfinite(error)) {
      if (attempts >= kMaxTreeSubsteps) return;  // left as at the last kept sub-step (finite)
      sub *= 0.2;
      continue;
    }
    if (error <= 1.0 || attempts >= kMaxTreeSubsteps) {
      q = s.stageQ;  // stage 6 is the 5th-order solution; its derivative starts the next sub-step
      qd = s.stageQd;
      std::swap(kq[0], kq[6]);
      std::swap(kv[0], kv[6]);
      left = sub == left ? 0.0 : left - sub;
      ++s.substeps;
    }
    sub *= factor;
  }
}

void stepArticulation(const joints::tree::Articulation& articulation, Eigen::VectorXd& q,
                      Eigen::VectorXd& qd, const Eigen::VectorXd& tau, double h,
                      std::span<const geometry::Vector6d> linkWrenches) {
  qd = predictArticulationVelocity(articulation, q, qd, tau, h, linkWrenches);
  integrateConfiguration(articulation, q, qd, h);
}

}  // namespace coulomb::integrators
