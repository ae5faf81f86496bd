#include <gtest/gtest.h>
#include <coulomb/solvers/bgs/LocalContactSolver.hpp>

#include <Eigen/SVD>

#include <random>

using namespace coulomb::solvers;

TEST(LocalContactSolver, ClosedFormStages) {
  const LocalContactData d = LocalContactData::from(Eigen::Vector3d(2, 1, 1).asDiagonal());
  auto solve = [&](const Eigen::Vector3d& q, double mu) {
    return solveLocalContact(d, q, mu, Eigen::Vector3d::Zero());
  };
  EXPECT_EQ(solve(Eigen::Vector3d(1, 5, 5), 0.5).stage, LocalStage::TakeOff);
  EXPECT_EQ(solve(Eigen::Vector3d(-2, 5, 5), 0.0).stage, LocalStage::Frictionless);
  EXPECT_EQ(solve(Eigen::Vector3d(-2, 0.1, 0.1), 0.5).stage, LocalStage::Stick);
  const LocalResult slip = solve(Eigen::Vector3d(-2, 3, 4), 0.5);
  EXPECT_EQ(slip.stage, LocalStage::IsotropicSlip);
  EXPECT_LT((slip.r - Eigen::Vector3d(1, -0.3, -0.4)).norm(), 1e-15);
}

// docs/solver-derivations.md section 4 check: random local problems of four families at scales
// 1e-6..1e6 are all solved to the local tolerance 1e-14 (20 000 in the prototype; 2 000 here).
TEST(LocalContactSolver, RandomProblemsAllScalesAndConditionings) {
  std::mt19937 rng(1);
  std::normal_distribution<double> g(0, 1);
  std::uniform_real_distribution<double> U(0, 1);
  int worst = 0;
  double worstError = 0;
  for (int k = 0; k < 2000; ++k) {
    Eigen::Matrix3d A;
    for (int i = 0; i < 9; ++i) A(i / 3, i % 3) = g(rng);
    Eigen::Matrix3d W = A * A.transpose() + 0.1 * Eigen::Matrix3d::Identity();
    const int family = k % 4;
    if (family == 0) W = Eigen::Vector3d(1 + U(rng), 1 + U(rng), 1).asDiagonal();  // isotropic-ish
    if (family == 2) {                                                             // cond 1e6
      Eigen::JacobiSVD<Eigen::Matrix3d> svd(W, Eigen::ComputeFullU);
      W = svd.matrixU() * Eigen::Vector3d(1, 1e-3, 1e-6).asDiagonal() * svd.matrixU().transpose();
    }
    if (family == 3) {  // non-symmetric, symmetric part unchanged (positive definite)
      const Eigen::Matrix3d R = Eigen::Matrix3d::Random();
      W += 0.05 * W.norm() * (R - R.transpose());
    }
    const double scale = std::pow(10.0, 12 * U(rng) - 6);
    W *= scale;
    const double mus[] = {0.1, 0.5, 1.0, 2.0};
    const double mu = mus[k % 4 == 0 ? (k / 4) % 4 : k % 4];
    const Eigen::Vector3d q(g(rng), g(rng), g(rng));
    const LocalContactData d = LocalContactData::from(W);
    const LocalResult res = solveLocalContact(d, q, mu, Eigen::Vector3d::Zero());
    EXPECT_TRUE(res.r.allFinite());
    if (res.error > worstError) worstError = res.error, worst = k;
  }
  EXPECT_LE(worstError, 1e-12) << "worst case " << worst;
}

TEST(LocalContactSolver, NeverWorseThanIncoming) {
  Eigen::Matrix3d W;
  W << 1.0, 0.9, 0.0, 0.9, 1.0, 0.0, 0.0, 0.0, 1e-3;
  const LocalContactData d = LocalContactData::from(W);
  const Eigen::Vector3d q(-1, 0.5, -2);
  const LocalResult res = solveLocalContact(d, q, 0.8, Eigen::Vector3d(0.5, 0, 0));
  EXPECT_LE(res.error, localError(d, q, 0.8, Eigen::Vector3d(0.5, 0, 0)));
  const LocalResult n = localNewton(d, q, 0.8, res.r, LocalSolverSettings{});
  EXPECT_LE(n.error, res.error);
}
