#include <gtest/gtest.h>
#include <coulomb/solvers/CoulombLaw.hpp>

#include <cmath>
#include <limits>
#include <random>

using namespace coulomb::solvers;

TEST(CoulombLaw, ConeProjectionBranchesAndMoreau) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> U(-1, 1);
  for (double mu : {0.0, 1e-3, 0.3, 1.0, 5.0}) {
    for (int k = 0; k < 2000; ++k) {
      const double scale = std::pow(10.0, 8 * U(rng));
      const Eigen::Vector3d x(scale * U(rng), scale * U(rng), scale * U(rng));
      const Eigen::Vector3d p = projectOntoCone(x, mu);
      EXPECT_LE(std::hypot(p[1], p[2]), mu * p[0] + 1e-15 * scale);   // in K
      EXPECT_LT((projectOntoCone(p, mu) - p).norm(), 1e-15 * scale);  // idempotent
      const Eigen::Vector3d d = projectOntoDualCone(-x, mu);
      EXPECT_LT((x - (p - d)).norm(), 4e-15 * scale);        // Moreau (2.3)
      EXPECT_LT(std::abs(p.dot(d)), 4e-15 * scale * scale);  // orthogonal
    }
  }
  // mu = 0 and x_N < 0: the x_N >= 0 test of (2.1a) matters.
  EXPECT_EQ(projectOntoCone(Eigen::Vector3d(-1, 0, 0), 0.0), Eigen::Vector3d::Zero());
}

TEST(CoulombLaw, EllipticConeProjectionIsTheClosestPoint) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> U(-1, 1);
  const double m1 = 0.2, m2 = 0.9;
  for (int k = 0; k < 500; ++k) {
    const Eigen::Vector3d x(U(rng), U(rng), U(rng));
    const Eigen::Vector3d p = projectOntoEllipticCone(x, m1, m2);
    EXPECT_LE(std::hypot(p[1] / m1, p[2] / m2), p[0] + 1e-12);
    // Variational inequality <x - p, z - p> <= 0 for sampled z in K.
    for (int t = 0; t < 20; ++t) {
      const double zn = std::abs(U(rng)) * 2, th = 3.2 * U(rng), s = std::abs(U(rng));
      const Eigen::Vector3d z(zn, zn * s * m1 * std::cos(th), zn * s * m2 * std::sin(th));
      EXPECT_LE((x - p).dot(z - p), 1e-12);
    }
  }
  const Eigen::Vector3d x(0.3, 1.0, -2.0);
  EXPECT_LT((projectOntoEllipticCone(x, 0.5, 0.5) - projectOntoCone(x, 0.5)).norm(), 1e-15);
  EXPECT_DOUBLE_EQ(projectOntoEllipticCone(x, 0.0, 0.5)[1], 0.0);
}

TEST(CoulombLaw, DiskShiftAndRegimes) {
  EXPECT_LT((projectOntoDisk(Eigen::Vector2d(3, 4), 1.0) - Eigen::Vector2d(0.6, 0.8)).norm(),
            1e-15);
  EXPECT_EQ(projectOntoDisk(Eigen::Vector2d(3, 4), 0.0), Eigen::Vector2d::Zero());
  EXPECT_DOUBLE_EQ(deSaxceShift(Eigen::Vector3d(1, 3, 4), 0.5)[0], 3.5);
  EXPECT_EQ(classifyContact(Eigen::Vector3d::Zero(), Eigen::Vector3d(1, 2, 0), 0.5),
            ContactRegime::TakeOff);
  EXPECT_EQ(classifyContact(Eigen::Vector3d(1, 0.1, 0), Eigen::Vector3d::Zero(), 0.5),
            ContactRegime::Stick);
  EXPECT_EQ(classifyContact(Eigen::Vector3d(1, -0.3, -0.4), Eigen::Vector3d(0, 3, 4), 0.5),
            ContactRegime::Slip);
  EXPECT_EQ(classifyContact(Eigen::Vector3d(1, 0.3, 0.4), Eigen::Vector3d(0, 3, 4), 0.5),
            ContactRegime::Violated);
  EXPECT_STREQ(contactRegimeName(ContactRegime::Slip), "slip");
}

// tangentNorm (the Coulomb law's replacement of std::hypot) agrees with std::hypot to round-off
// over the whole range, including the scaled ends and zeros; the cone projection agrees with the
// same projection computed with std::hypot (fc3d_project_cone's) likewise.
TEST(CoulombLaw, TangentNormMatchesHypot) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> mant(-1.0, 1.0);
  std::uniform_int_distribution<int> expo(-1000, 1000);
  for (int t = 0; t < 20000; ++t) {
    const double a = std::ldexp(mant(rng), expo(rng)), b = std::ldexp(mant(rng), expo(rng));
    const double h = std::hypot(a, b);
    EXPECT_NEAR(tangentNorm(a, b), h, 6e-16 * h) << a << " " << b;
    const double mu = 0.5 + 0.5 * mant(rng);
    double x[3] = {mant(rng), mant(rng), mant(rng)}, y[3] = {x[0], x[1], x[2]};
    projectOntoCone(x, mu);
    const double yT = std::hypot(y[1], y[2]);  // (2.1) with std::hypot
    if (!(y[0] >= 0 && yT <= mu * y[0])) {
      const double n = mu * yT <= -y[0] ? 0.0 : (y[0] + mu * yT) / (1.0 + mu * mu);
      y[0] = n;
      y[1] = yT > 0 ? y[1] * mu * n / yT : 0.0;
      y[2] = yT > 0 ? y[2] * mu * n / yT : 0.0;
    }
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(x[k], y[k], 1e-15);
  }
  EXPECT_EQ(tangentNorm(0.0, 0.0), 0.0);
  EXPECT_EQ(tangentNorm(-0.0, 0.0), 0.0);
  EXPECT_EQ(tangentNorm(1e-200, 0.0), 1e-200);                     // a^2 underflows: std::hypot
  EXPECT_EQ(tangentNorm(3e200, 4e200), std::hypot(3e200, 4e200));  // a^2 overflows
  EXPECT_TRUE(std::isinf(tangentNorm(std::numeric_limits<double>::infinity(), 1.0)));
  EXPECT_TRUE(std::isnan(tangentNorm(std::numeric_limits<double>::quiet_NaN(), 1.0)));
}
