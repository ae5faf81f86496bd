#include <gtest/gtest.h>
#include <coulomb/solvers/lemke/LemkeLcp.hpp>

#include <Eigen/Dense>

#include <random>

using namespace coulomb::solvers;

TEST(LemkeLcp, TextbookTwoByTwo) {
  // M = [[2, 1], [1, 2]], b = (-5, -6): both z > 0, w = 0 -> z = (4/3, 7/3).
  Eigen::MatrixXd M(2, 2);
  M << 2, 1, 1, 2;
  const LcpResult out = solveLcpLemke(M, Eigen::Vector2d(-5, -6));
  ASSERT_EQ(out.status, LcpStatus::Solved);
  EXPECT_NEAR(out.z[0], 4.0 / 3.0, 1e-14);
  EXPECT_NEAR(out.z[1], 7.0 / 3.0, 1e-14);
  EXPECT_LT(out.error, 1e-15);
}

TEST(LemkeLcp, NonNegativeRightHandSideIsZero) {
  const LcpResult out = solveLcpLemke(Eigen::MatrixXd::Identity(3, 3), Eigen::Vector3d(1, 0, 2));
  EXPECT_EQ(out.status, LcpStatus::Solved);
  EXPECT_EQ(out.pivots, 0);
  EXPECT_EQ(out.z, Eigen::Vector3d::Zero());
}

// Kostreva's degenerate example (all b equal, cyclic M): with ties broken by the smallest row
// index Lemke cycles until the pivot limit; the lexicographic rule solves it.
TEST(LemkeLcp, LexicographicRuleStopsCycling) {
  Eigen::MatrixXd M(3, 3);
  M << 1, 2, 0, 0, 1, 2, 2, 0, 1;
  const Eigen::Vector3d b(-1, -1, -1);
  LemkeSettings plain;
  plain.lexicographic = false;
  plain.perturbation = 0;  // the perturbation alone also breaks these ties
  plain.maxPivots = 100;
  EXPECT_EQ(solveLcpLemke(M, b, plain).status, LcpStatus::PivotLimit);
  LemkeSettings lexOnly;
  lexOnly.perturbation = 0;
  const LcpResult lex = solveLcpLemke(M, b, lexOnly);
  ASSERT_EQ(lex.status, LcpStatus::Solved);
  EXPECT_LT(lex.error, 1e-14);
  EXPECT_LE(lex.pivots, 10);
}

TEST(LemkeLcp, PerturbationAloneStopsCyclingAndKeepsTheAnswerExact) {
  Eigen::MatrixXd M(3, 3);
  M << 1, 2, 0, 0, 1, 2, 2, 0, 1;
  LemkeSettings perturbedOnly;
  perturbedOnly.lexicographic = false;
  perturbedOnly.maxPivots = 100;
  const LcpResult out = solveLcpLemke(M, Eigen::Vector3d(-1, -1, -1), perturbedOnly);
  ASSERT_EQ(out.status, LcpStatus::Solved);
  EXPECT_LT(out.error, 1e-15);  // the final basis solved with the true b
}

TEST(LemkeLcp, RayOnInfeasibleProblem) {
  // w = -z - 1 can never be >= 0 with z >= 0: secondary ray.
  const LcpResult out =
      solveLcpLemke(-Eigen::MatrixXd::Identity(1, 1), Eigen::VectorXd::Constant(1, -1));
  EXPECT_EQ(out.status, LcpStatus::Ray);
  EXPECT_TRUE(out.z.allFinite());
}

TEST(LemkeLcp, RandomPositiveDefiniteProblemsAreSolved) {
  std::mt19937 rng(11);
  std::normal_distribution<double> g(0.0, 1.0);
  for (int k = 0; k < 50; ++k) {
    const int n = 2 + k % 9;
    Eigen::MatrixXd A(n, n);
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) A(i, j) = g(rng);
    const Eigen::MatrixXd M = A * A.transpose() + 0.1 * Eigen::MatrixXd::Identity(n, n);
    Eigen::VectorXd b(n);
    for (int i = 0; i < n; ++i) b[i] = g(rng);
    const LcpResult out = solveLcpLemke(M, b);
    ASSERT_EQ(out.status, LcpStatus::Solved) << k;
    EXPECT_LT(out.error, 1e-12) << k;
  }
}
