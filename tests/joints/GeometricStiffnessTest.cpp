// joints/GeometricStiffness: K = [f]x [r]x against finite differences of the torque r x f as the
// body turns, and the stabilizing inertia against the explicit stability limit omega h = 2 (and its
// shortcut against the eigen-decomposition).
#include <gtest/gtest.h>
#include <coulomb/joints/GeometricStiffness.hpp>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>

#include <cmath>
#include <random>

using namespace coulomb;

TEST(GeometricStiffness, MatchesTheTorqueChangeOfATurnedArm) {
  const Eigen::Vector3d force(3.0, -1.0, 2.0), arm(0.2, 0.5, -0.4);
  const Eigen::Matrix3d k = joints::rotationalGeometricStiffness(force, arm);
  const double eps = 1e-7;
  for (int axis = 0; axis < 3; ++axis) {
    const Eigen::Matrix3d turn(Eigen::AngleAxisd(eps, Eigen::Vector3d::Unit(axis)));
    const Eigen::Matrix3d back(Eigen::AngleAxisd(-eps, Eigen::Vector3d::Unit(axis)));
    const Eigen::Vector3d difference =
        ((turn * arm).cross(force) - (back * arm).cross(force)) / (2.0 * eps);
    EXPECT_LT((difference - k.col(axis)).norm(), 1e-7) << "axis " << axis;
  }
}

TEST(GeometricStiffness, TensionOnALinkRestoresItsTransverseAxes) {
  // A link along z pulled at both ends by T: k = -T L on x and y, nothing about its own axis.
  const double tension = 98.1, length = 0.1;
  const Eigen::Matrix3d k =
      joints::rotationalGeometricStiffness({0, 0, tension}, {0, 0, length / 2}) +
      joints::rotationalGeometricStiffness({0, 0, -tension}, {0, 0, -length / 2});
  EXPECT_NEAR(k(0, 0), -tension * length, 1e-12);
  EXPECT_NEAR(k(1, 1), -tension * length, 1e-12);
  EXPECT_NEAR(k(2, 2), 0.0, 1e-12);
}

TEST(GeometricStiffness, InertiaIsRaisedOnlyBeyondTheExplicitLimit) {
  const Eigen::Matrix3d inertia = Eigen::Vector3d(4.857e-6, 7.557e-5, 7.557e-5).asDiagonal();
  const double h = 0.01;
  // A link along x. omega h = 1.9 about y and z: stable, unchanged.
  const double stable = 1.9 * 1.9 * 7.557e-5 / (h * h);
  const Eigen::Matrix3d k = Eigen::Vector3d(0.0, -stable, -stable).asDiagonal();
  EXPECT_EQ(joints::stabilizingInertia(inertia, k, h), inertia);
  // The heavy-load chain: T L = 9.81 N m, omega h = 3.6 -> raised to omega h = sqrt(2) on y, z.
  const Eigen::Matrix3d loaded = Eigen::Vector3d(0.0, -9.81, -9.81).asDiagonal();
  const Eigen::Matrix3d raised = joints::stabilizingInertia(inertia, loaded, h);
  EXPECT_EQ(raised(0, 0), inertia(0, 0));
  EXPECT_NEAR(raised(1, 1), 0.5 * h * h * 9.81, 1e-15);
  EXPECT_NEAR(raised(2, 2), 0.5 * h * h * 9.81, 1e-15);
  EXPECT_NEAR(h * h * 9.81 / raised(1, 1), 2.0, 1e-12);  // (omega h)^2
}

TEST(GeometricStiffness, ShortcutAgreesWithTheEigenDecomposition) {
  // stabilizingInertia skips its eigen-decomposition when 16 I^2 - h^4 S^2 is positive definite;
  // against the rule applied to every eigenpair, on random inertias and loads around the limit.
  std::mt19937 rng(17);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const double h = 0.01;
  int unchanged = 0, raised = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    const Eigen::Matrix3d rotation =
        Eigen::Quaterniond(Eigen::Vector4d(u(rng), u(rng), u(rng), u(rng)).normalized())
            .toRotationMatrix();
    const Eigen::Vector3d moments(1e-5 * (1.0 + 9.0 * std::abs(u(rng))),
                                  1e-4 * (1.0 + std::abs(u(rng))), 1e-4 * (1.0 + std::abs(u(rng))));
    const Eigen::Matrix3d inertia = rotation * moments.asDiagonal() * rotation.transpose();
    Eigen::Matrix3d k = Eigen::Matrix3d::Zero();
    const double load = 4.0 * 1e-4 / (h * h) * 40.0 * std::abs(u(rng));  // |k| to ~8x the limit
    for (int joint = 0; joint < 2; ++joint)
      k += joints::rotationalGeometricStiffness(load * Eigen::Vector3d(u(rng), u(rng), u(rng)),
                                                0.05 * Eigen::Vector3d(u(rng), u(rng), u(rng)));
    // The rule on every eigenpair (joints/GeometricStiffness.hpp).
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(0.5 * (k + k.transpose()));
    Eigen::Matrix3d expected = inertia;
    for (int j = 0; j < 3; ++j) {
      const Eigen::Vector3d v = eigen.eigenvectors().col(j);
      const double stiff = h * h * std::abs(eigen.eigenvalues()(j)), current = v.dot(inertia * v);
      if (stiff > 4.0 * current) expected += (0.5 * stiff - current) * v * v.transpose();
    }
    const Eigen::Matrix3d got = joints::stabilizingInertia(inertia, k, h);
    if (expected == inertia) {
      ++unchanged;
      EXPECT_EQ(got, inertia) << "trial " << trial;
    } else {
      ++raised;
      EXPECT_LT((got - expected).norm(), 1e-12 * expected.norm()) << "trial " << trial;
    }
  }
  EXPECT_GT(unchanged, 200);  // both outcomes are exercised
  EXPECT_GT(raised, 200);
}
