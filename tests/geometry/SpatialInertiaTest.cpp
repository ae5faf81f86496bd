#include <gtest/gtest.h>
#include <coulomb/geometry/SpatialInertia.hpp>

#include <limits>

using namespace coulomb::geometry;

TEST(SpatialInertia, TwoPointLikeMassesGiveTheParallelAxisSum) {
  const SpatialInertia a{1.0, Eigen::Vector3d(-1, 0, 0), Eigen::Matrix3d::Identity()};
  const SpatialInertia b{3.0, Eigen::Vector3d(1, 0, 0), Eigen::Matrix3d::Identity()};
  const SpatialInertia sum = a + b;
  EXPECT_DOUBLE_EQ(sum.mass, 4.0);
  EXPECT_TRUE(sum.centerOfMass.isApprox(Eigen::Vector3d(0.5, 0, 0)));
  // about the combined COM: 1 * 1.5^2 + 3 * 0.5^2 = 3 around y and z, nothing around x.
  EXPECT_NEAR(sum.inertiaAboutCom(0, 0), 2.0, 1e-12);
  EXPECT_NEAR(sum.inertiaAboutCom(1, 1), 2.0 + 3.0, 1e-12);
  EXPECT_NEAR(sum.inertiaAboutCom(2, 2), 2.0 + 3.0, 1e-12);
}

TEST(SpatialInertia, MatrixIsFeatherstoneForm) {
  const SpatialInertia body{2.0, Eigen::Vector3d(0.1, 0.2, 0.3), Eigen::Matrix3d::Identity()};
  const Matrix6d m = body.matrix();
  EXPECT_TRUE(m.isApprox(m.transpose()));
  // Kinetic energy of a pure translation v is m v^2 / 2 whatever the COM.
  const Vector6d v = motionVector(Eigen::Vector3d::Zero(), Eigen::Vector3d(1, 2, 3));
  EXPECT_NEAR(0.5 * v.dot(m * v), 0.5 * 2.0 * 14.0, 1e-12);
}

TEST(SpatialInertia, TransformedRotatesTheInertia) {
  const SpatialInertia rod{1.0, Eigen::Vector3d::Zero(), Eigen::Vector3d(0.01, 1, 1).asDiagonal()};
  Pose pose;
  pose.rotation = Eigen::AngleAxisd(EIGEN_PI / 2, Eigen::Vector3d::UnitZ());
  pose.position = Eigen::Vector3d(0, 0, 2);
  const SpatialInertia moved = rod.transformed(pose);
  EXPECT_NEAR(moved.inertiaAboutCom(1, 1), 0.01, 1e-12);  // the rod's axis now along y
  EXPECT_TRUE(moved.centerOfMass.isApprox(Eigen::Vector3d(0, 0, 2)));
}

TEST(SpatialInertia, PrincipalAxesDiagonalise) {
  const Eigen::Matrix3d r = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 1, 0).normalized()).matrix();
  const Eigen::Matrix3d inertia = r * Eigen::Vector3d(1, 2, 3).asDiagonal() * r.transpose();
  const PrincipalAxes axes = principalAxes(inertia);
  EXPECT_TRUE(axes.moments.isApprox(Eigen::Vector3d(1, 2, 3), 1e-12));
  const Eigen::Matrix3d p = axes.rotation.toRotationMatrix();
  EXPECT_TRUE((p * axes.moments.asDiagonal() * p.transpose()).isApprox(inertia, 1e-12));
  EXPECT_NEAR(p.determinant(), 1.0, 1e-12);
}

TEST(SpatialInertia, ValidityCheckNamesTheWrongValue) {
  const Eigen::Matrix3d good = Eigen::Vector3d(1, 1, 1.5).asDiagonal();
  EXPECT_FALSE(checkPhysicalValidity(1.0, good).has_value());
  // A flat plate is the limit case I_x + I_y = I_z: accepted.
  EXPECT_FALSE(checkPhysicalValidity(1.0, Eigen::Vector3d(1, 1, 2).asDiagonal()).has_value());

  auto message = [](double mass, const Eigen::Matrix3d& inertia) {
    return checkPhysicalValidity(mass, inertia).value_or("");
  };
  EXPECT_NE(message(0.0, good).find("mass"), std::string::npos);
  EXPECT_NE(message(-2.0, good).find("got -2"), std::string::npos);
  EXPECT_NE(message(std::numeric_limits<double>::infinity(), good).find("mass"), std::string::npos);
  Eigen::Matrix3d nan = good;
  nan(1, 2) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_NE(message(1.0, nan).find("inertia[1][2]"), std::string::npos);
  Eigen::Matrix3d asymmetric = good;
  asymmetric(0, 1) = 0.1;
  EXPECT_NE(message(1.0, asymmetric).find("not symmetric"), std::string::npos);
  EXPECT_NE(message(1.0, Eigen::Vector3d(1, -1, 1).asDiagonal()).find("positive definite"),
            std::string::npos);
  const std::string triangle = message(1.0, Eigen::Vector3d(1, 1, 3).asDiagonal());
  EXPECT_NE(triangle.find("triangle inequality"), std::string::npos);
  EXPECT_NE(triangle.find("3"), std::string::npos);
}
