#include <gtest/gtest.h>
#include <coulomb/geometry/Quaternion.hpp>

#include <numbers>

using namespace coulomb::geometry;

TEST(Quaternion, ExpMatchesAngleAxis) {
  const Eigen::Vector3d axis = Eigen::Vector3d(1, -2, 0.5).normalized();
  for (double angle : {1e-9, 1e-5, 0.3, 2.0, 3.1, 7.0}) {
    const Eigen::Quaterniond expected(Eigen::AngleAxisd(angle, axis));
    EXPECT_TRUE(quaternionExp(angle * axis).isApprox(expected, 1e-14)) << angle;
  }
  EXPECT_TRUE(quaternionExp(Eigen::Vector3d::Zero()).isApprox(Eigen::Quaterniond::Identity()));
}

TEST(Quaternion, LogInvertsExpOnTheShortArc) {
  for (const Eigen::Vector3d& phi :
       {Eigen::Vector3d(0.1, 0.2, -0.3), Eigen::Vector3d(1e-10, 0, 0), Eigen::Vector3d(0, 3.0, 0)})
    EXPECT_TRUE(quaternionLog(quaternionExp(phi)).isApprox(phi, 1e-12)) << phi.transpose();
  // -q is the same rotation: the log picks the short arc.
  const Eigen::Quaterniond q = quaternionExp(Eigen::Vector3d(0, 0, 1));
  Eigen::Quaterniond minusQ = q;
  minusQ.coeffs() = -q.coeffs();
  EXPECT_TRUE(quaternionLog(minusQ).isApprox(Eigen::Vector3d(0, 0, 1), 1e-12));
}

TEST(Quaternion, WorldAndBodyIntegrationAgreeForSpinAboutTheirCommonAxis) {
  const Eigen::Quaterniond q = axisRotation(2, 0.5);
  const Eigen::Vector3d omega(0, 0, 2.0);  // z in body == z in world for a rotation about z
  EXPECT_TRUE(integrateWorldRotation(q, omega, 0.25).isApprox(axisRotation(2, 1.0), 1e-14));
  EXPECT_TRUE(integrateBodyRotation(q, omega, 0.25).isApprox(axisRotation(2, 1.0), 1e-14));
}

TEST(Quaternion, BodyRateIsWorldRateSeenFromTheBody) {
  const Eigen::Quaterniond q = quaternionExp(Eigen::Vector3d(0.3, -0.2, 0.9));
  const Eigen::Vector3d omegaWorld(0.4, 1.0, -0.7);
  const Eigen::Vector3d omegaBody = q.conjugate() * omegaWorld;
  EXPECT_TRUE(integrateWorldRotation(q, omegaWorld, 0.1)
                  .isApprox(integrateBodyRotation(q, omegaBody, 0.1), 1e-14));
}
