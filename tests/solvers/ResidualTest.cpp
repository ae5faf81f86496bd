#include <gtest/gtest.h>
#include <coulomb/solvers/Residual.hpp>

#include <fc3d_text.hpp>  // the corpus' reference reader and residual (tests/data/fc3d)

#include <random>

#include "TestProblems.hpp"

using namespace coulomb::solvers;

TEST(Residual, MatchesTheReferenceOnFixtures) {
  std::mt19937 rng(11);
  std::normal_distribution<double> g(0, 1);
  for (const char* name : fixtures::kFixtures) {
    const ContactProblem p = fixtures::loadFixture(name);
    Fc3dProblem ref;
    ASSERT_EQ(fc3d_read(std::string(COULOMB_TEST_DATA_DIR) + "/fc3d/" + name + ".fc3d", ref), "");
    for (int trial = 0; trial < 4; ++trial) {
      Eigen::VectorXd r = Eigen::VectorXd::Zero(p.size());
      if (trial > 0)
        for (int i = 0; i < p.size(); ++i) r[i] = g(rng) * std::pow(10.0, trial - 2);
      const ResidualValue v = commonResidual(p, r);
      const double expected = fc3d_natural_map_residual(ref, r.data());
      // To round-off: the reference's std::hypot is tangentNorm here.
      EXPECT_NEAR(v.absolute, expected, 1e-14 * (1.0 + expected)) << name << " trial " << trial;
      EXPECT_NEAR(v.relative, expected / (1.0 + fc3d_norm(ref.q)), 1e-14 * (1.0 + expected));
    }
  }
}

TEST(Residual, ZeroAtAnalyticSolutionsAndScalarRows) {
  // Slip: W = I, q = (-1, 3, 4), mu = 0.5 -> r = (1, -0.3, -0.4), u = (0, 2.7, 3.6).
  const ContactProblem slip =
      fixtures::singleContact(Eigen::Matrix3d::Identity(), Eigen::Vector3d(-1, 3, 4), 0.5);
  EXPECT_LT(commonResidual(slip, Eigen::Vector3d(1, -0.3, -0.4)).absolute, 1e-15);
  EXPECT_GT(commonResidual(slip, Eigen::Vector3d(1, 0.3, -0.4)).absolute, 0.1);
  // Scalar rows (10.1): equality u = 0, unilateral min(r, u), bounded box.
  ContactProblem p;
  p.blocks = {ConstraintBlock::equality(), ConstraintBlock::unilateral(),
              ConstraintBlock::bounded(-0.5, 0.5)};
  p.W = DelassusOperator::dense(Eigen::Matrix3d::Identity());
  p.q = Eigen::Vector3d(-2, 3, -1);
  EXPECT_LT(commonResidual(p, Eigen::Vector3d(2, 0, 0.5)).absolute, 1e-15);  // u = (0, 3, -0.5)
  EXPECT_NEAR(commonResidual(p, Eigen::Vector3d(0, 0, 0.5)).absolute, 2.0, 1e-15);
  EXPECT_NEAR(commonResidual(p, Eigen::Vector3d(2, 0, 0.5)).relative, 0.0, 1e-15);
  // Anisotropic slip along T1 with mu1 = 0.2: r_T = -mu1 r_N e1.
  ContactProblem a;
  a.blocks = {ConstraintBlock::anisotropicContact(0.2, 0.8)};
  a.W = DelassusOperator::dense(Eigen::Matrix3d::Identity());
  a.q = Eigen::Vector3d(-1, 5, 0);
  EXPECT_LT(commonResidual(a, Eigen::Vector3d(1, -0.2, 0)).absolute, 1e-15);
  EXPECT_GT(commonResidual(a, Eigen::Vector3d(1, -0.8, 0)).absolute, 0.1);
  EXPECT_DOUBLE_EQ(plainNorm(Eigen::Vector2d(3, 4)), 5.0);
}
