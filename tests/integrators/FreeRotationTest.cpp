// The torque-free rotation (DLM splitting) against the invariants of the free rigid body.
#include <gtest/gtest.h>
#include <coulomb/geometry/BodyState.hpp>
#include <coulomb/geometry/Quaternion.hpp>
#include <coulomb/integrators/FreeRotation.hpp>
#include <coulomb/integrators/PositionUpdate.hpp>

#include <cmath>
#include <cstdio>

using namespace coulomb;
using geometry::BodyState;
using geometry::MotionType;

namespace {

// One dynamic body with an asymmetric, non-diagonal inertia (principal frame is not the body
// frame).
BodyState asymmetricBody(const Eigen::Vector3d& omega) {
  BodyState state;
  const Eigen::Matrix3d rotation =
      Eigen::AngleAxisd(0.4, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  const Eigen::Matrix3d inertia =
      rotation * Eigen::Vector3d(1.0, 2.0, 2.5).asDiagonal() * rotation.transpose();
  geometry::Pose pose;
  pose.rotation = Eigen::Quaterniond(Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitY()));
  state.assign(0, MotionType::Dynamic, pose, Eigen::Vector3d::Zero(), omega, 1.0, inertia);
  return state;
}

}  // namespace

TEST(FreeRotation, WorldAngularMomentumConservedOver10000Steps) {
  BodyState state = asymmetricBody(Eigen::Vector3d(0.3, 2.0, -1.1));
  const Eigen::Vector3d initialMomentum = state.angularMomentum(0);
  const double initialEnergy = state.kineticEnergy(0);
  double maxMomentumDrift = 0.0, maxEnergyDrift = 0.0;
  for (int step = 0; step < 10000; ++step) {
    integrators::integratePositions(state, 0.01);
    maxMomentumDrift =
        std::max(maxMomentumDrift,
                 (state.angularMomentum(0) - initialMomentum).norm() / initialMomentum.norm());
    maxEnergyDrift =
        std::max(maxEnergyDrift, std::abs(state.kineticEnergy(0) - initialEnergy) / initialEnergy);
  }
  std::printf("max relative |dL| = %.3e, max relative |dE| = %.3e over 10000 steps, h = 0.01\n",
              maxMomentumDrift, maxEnergyDrift);
  EXPECT_LT(maxMomentumDrift, 1e-9);
  // Symplectic splitting: energy error stays bounded, O(h^2), no secular drift.
  EXPECT_LT(maxEnergyDrift, 1e-3);
}

TEST(FreeRotation, EnergyErrorIsSecondOrder) {
  auto energyError = [](double h) {
    BodyState state = asymmetricBody(Eigen::Vector3d(0.3, 2.0, -1.1));
    const double e0 = state.kineticEnergy(0);
    double worst = 0.0;
    for (double t = 0.0; t < 10.0; t += h) {
      integrators::integratePositions(state, h);
      worst = std::max(worst, std::abs(state.kineticEnergy(0) - e0));
    }
    return worst;
  };
  const double ratio = energyError(0.02) / energyError(0.01);
  EXPECT_GT(ratio, 3.0);  // ~4 for a second-order method
  EXPECT_LT(ratio, 5.0);
}

TEST(FreeRotation, SpinAt1000RadPerSecondStaysFiniteAndBounded) {
  // 10 rad per step: far too coarse to be accurate, but every invariant of the splitting holds.
  BodyState state = asymmetricBody(Eigen::Vector3d(1000.0, 20.0, -5.0));
  const Eigen::Vector3d initialMomentum = state.angularMomentum(0);
  const double l2 = initialMomentum.squaredNorm();
  const double minMoment = 1.0, maxMoment = 2.5;
  for (int step = 0; step < 10000; ++step) {
    integrators::integratePositions(state, 0.01);
    ASSERT_TRUE(state.angularVelocities[0].allFinite());
    ASSERT_TRUE(state.poses[0].rotation.coeffs().allFinite());
    // |pi| = |L| is preserved, so the energy stays in [L^2 / 2 I_max, L^2 / 2 I_min] and
    // |omega| <= |L| / I_min: the body cannot gain energy, whatever the step size.
    const double energy = state.kineticEnergy(0);
    ASSERT_LE(energy, l2 / (2.0 * minMoment) * (1.0 + 1e-9));
    ASSERT_GE(energy, l2 / (2.0 * maxMoment) * (1.0 - 1e-9));
    ASSERT_LE(state.angularVelocities[0].norm(), std::sqrt(l2) / minMoment * (1.0 + 1e-9));
  }
  EXPECT_LT((state.angularMomentum(0) - initialMomentum).norm() / std::sqrt(l2), 1e-9);
  EXPECT_NEAR(state.poses[0].rotation.norm(), 1.0, 1e-12);
}

TEST(FreeRotation, SpinAboutAPrincipalAxisIsExact) {
  // A steady spin about a principal axis is a fixed point of every sub-rotation: exact angle.
  const Eigen::Quaterniond start = Eigen::Quaterniond::Identity();
  const Eigen::Vector3d moments(1.0, 2.0, 3.0);
  Eigen::Quaterniond q = start;
  for (int i = 0; i < 100; ++i)
    q = integrators::rotateTorqueFree(q, Eigen::Quaterniond::Identity(), moments,
                                      Eigen::Vector3d(0.0, 0.0, 3.0 * 0.7), 0.01);
  EXPECT_TRUE(q.isApprox(geometry::axisRotation(2, 0.7), 1e-12));
}

TEST(FreeRotation, ClosedFormSubRotationsMatchQuaternionProducts) {
  // rotatePrincipalFrame writes Q R_k and R_k^T pi out for a coordinate axis k; the splitting
  // done with general quaternion products (DLM 1997, eqs. 3.5-3.7) must give the same flow.
  const Eigen::Vector3d moments(0.7, 1.3, 2.1);
  const Eigen::Quaterniond start =
      Eigen::Quaterniond(Eigen::AngleAxisd(1.1, Eigen::Vector3d(-2, 1, 3).normalized()));
  const Eigen::Vector3d bodyMomentum(1.9, -3.1, 4.3);
  for (const double h : {0.001, 0.01, 0.1}) {
    Eigen::Quaterniond q = start;
    Eigen::Vector3d pi = bodyMomentum;
    const auto subRotation = [&](int axis, double step) {
      const Eigen::Quaterniond r = geometry::axisRotation(axis, step * pi[axis] / moments[axis]);
      q = q * r;
      pi = r.conjugate() * pi;
    };
    // One sub-step: every axis turns by less than 1 rad (the sub-stepping bound).
    ASSERT_LT(h * bodyMomentum.cwiseQuotient(moments).cwiseAbs().maxCoeff(), 1.0);
    subRotation(0, 0.5 * h);
    subRotation(1, 0.5 * h);
    subRotation(2, h);
    subRotation(1, 0.5 * h);
    subRotation(0, 0.5 * h);
    const Eigen::Quaterniond closedForm =
        integrators::rotatePrincipalFrame(start, bodyMomentum, moments, h);
    EXPECT_LT((closedForm.coeffs() - q.coeffs()).norm(), 1e-14) << "h = " << h;
    // L = Q pi is conserved by the flow: the new frame carries the same world momentum.
    EXPECT_LT((closedForm * pi - start * bodyMomentum).norm(), 1e-13) << "h = " << h;
  }
}

TEST(FreeRotation, SymmetricTopsFollowTheExactFlow) {
  // Two equal moments: rotatePrincipalFrame takes the closed-form precession. Reference: the
  // equations of motion dQ/dt = [omega] Q, omega = Q I^-1 Q^T L (L constant), by RK4 with 20 000
  // steps (error ~1e-15 here).
  const Eigen::Quaterniond start =
      Eigen::Quaterniond(Eigen::AngleAxisd(0.8, Eigen::Vector3d(1, -2, 0.5).normalized()));
  const Eigen::Vector3d bodyMomentum(0.9, -1.7, 2.3);
  const Eigen::Vector3d world = start * bodyMomentum;
  for (const Eigen::Vector3d& moments :
       {Eigen::Vector3d(1.0, 1.0, 0.4), Eigen::Vector3d(0.5, 2.0, 2.0),
        Eigen::Vector3d(1.5, 0.3, 1.5), Eigen::Vector3d(0.7, 0.7, 0.7)}) {
    const double h = 0.2;
    const auto derivative = [&](const Eigen::Vector4d& c) {
      const Eigen::Quaterniond q(c[3], c[0], c[1], c[2]);
      const Eigen::Vector3d omega =
          q.normalized() * (q.normalized().conjugate() * world).cwiseQuotient(moments).eval();
      const Eigen::Quaterniond dq = Eigen::Quaterniond(0.0, omega.x(), omega.y(), omega.z()) * q;
      return Eigen::Vector4d(0.5 * dq.x(), 0.5 * dq.y(), 0.5 * dq.z(), 0.5 * dq.w());
    };
    Eigen::Vector4d c = start.coeffs();
    const int steps = 20000;
    const double dt = h / steps;
    for (int i = 0; i < steps; ++i) {
      const Eigen::Vector4d k1 = derivative(c), k2 = derivative(c + 0.5 * dt * k1),
                            k3 = derivative(c + 0.5 * dt * k2), k4 = derivative(c + dt * k3);
      c += dt / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
    }
    Eigen::Quaterniond reference(c[3], c[0], c[1], c[2]);
    reference.normalize();
    Eigen::Quaterniond exact = integrators::rotatePrincipalFrame(start, bodyMomentum, moments, h);
    if (exact.coeffs().dot(reference.coeffs()) < 0) exact.coeffs() *= -1.0;
    EXPECT_LT((exact.normalized().coeffs() - reference.coeffs()).norm(), 1e-11)
        << moments.transpose();
  }
}
