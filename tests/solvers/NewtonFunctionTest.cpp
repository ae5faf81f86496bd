#include <gtest/gtest.h>
#include <coulomb/solvers/CoulombLaw.hpp>
#include <coulomb/solvers/newton/NewtonFunction.hpp>

#include <random>

using namespace coulomb::solvers;

// A and B against central differences of Phi in u and r, every case (5.3)-(5.4), both radii.
TEST(NewtonFunction, JacobianBlocksMatchDifferences) {
  std::mt19937 rng(5);
  std::normal_distribution<double> g(0, 1);
  for (auto radius :
       {AlartCurnierFunction::Radius::PositivePart, AlartCurnierFunction::Radius::NormalImpulse}) {
    const AlartCurnierFunction f(radius);
    double worst = 0;
    for (int k = 0; k < 2000; ++k) {
      const Eigen::Vector3d r(g(rng), g(rng), g(rng)), u(g(rng), g(rng), g(rng));
      const double mu = 0.1 + std::abs(g(rng)), rn = 0.5 + std::abs(g(rng)),
                   rt = 0.5 + std::abs(g(rng));
      Eigen::Vector3d phi, p1, p2;
      Eigen::Matrix3d A, B, dummy1, dummy2;
      f.contact(r, u, mu, rn, rt, phi, A, B);
      const double h = 1e-7;
      for (int j = 0; j < 3; ++j) {
        const Eigen::Vector3d e = Eigen::Vector3d::Unit(j) * h;
        f.contact(r, u + e, mu, rn, rt, p1, dummy1, dummy2);
        f.contact(r, u - e, mu, rn, rt, p2, dummy1, dummy2);
        const Eigen::Vector3d du = (p1 - p2) / (2 * h);
        f.contact(r + e, u, mu, rn, rt, p1, dummy1, dummy2);
        f.contact(r - e, u, mu, rn, rt, p2, dummy1, dummy2);
        const Eigen::Vector3d dr = (p1 - p2) / (2 * h);
        const double err = std::max((du - A.col(j)).norm(), (dr - B.col(j)).norm());
        if (err < 1e-3)
          worst = std::max(worst, err);  // skip points next to a kink
        else
          ADD_FAILURE() << "kink or wrong derivative, err " << err;
      }
    }
    EXPECT_LT(worst, 1e-6);
  }
}

TEST(NewtonFunction, ZeroExactlyOnCoulombPairs) {
  const AlartCurnierFunction f;
  Eigen::Vector3d phi;
  Eigen::Matrix3d A, B;
  f.contact(Eigen::Vector3d::Zero(), Eigen::Vector3d(1, 2, 3), 0.5, 1, 1, phi, A, B);  // take-off
  EXPECT_EQ(phi.norm(), 0.0);
  f.contact(Eigen::Vector3d(1, 0.1, 0.2), Eigen::Vector3d::Zero(), 0.5, 1, 1, phi, A, B);  // stick
  EXPECT_EQ(phi.norm(), 0.0);
  f.contact(Eigen::Vector3d(1, -0.3, -0.4), Eigen::Vector3d(0, 3, 4), 0.5, 0.7, 2, phi, A, B);
  EXPECT_LT(phi.norm(), 1e-15);  // slip
  f.contact(Eigen::Vector3d(1, 0.3, -0.4), Eigen::Vector3d(0, 3, 4), 0.5, 1, 1, phi, A, B);
  EXPECT_GT(phi.norm(), 0.1);
}

TEST(NewtonFunction, ScalarRows) {
  const AlartCurnierFunction f;
  double phi, A, B;
  f.scalarRow(ConstraintBlock::equality(), 3.0, 0.5, 2.0, phi, A, B);
  EXPECT_DOUBLE_EQ(phi, 1.0);
  EXPECT_DOUBLE_EQ(A, 2.0);
  f.scalarRow(ConstraintBlock::bounded(-1, 1), 0.9, -1.0, 1.0, phi, A, B);  // at the upper bound
  EXPECT_DOUBLE_EQ(phi, -0.1);
  EXPECT_DOUBLE_EQ(B, 1.0);
  f.scalarRow(ConstraintBlock::unilateral(), 0.0, 2.0, 1.0, phi, A, B);  // separated
  EXPECT_DOUBLE_EQ(phi, 0.0);
}
