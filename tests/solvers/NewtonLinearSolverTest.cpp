#include <gtest/gtest.h>
#include <coulomb/solvers/newton/NewtonLinearSolver.hpp>
#include <coulomb/solvers/newton/NonsmoothNewton.hpp>

#include "TestProblems.hpp"

#include <Eigen/LU>

#include <random>

using namespace coulomb::solvers;

namespace {

// A tower of `bodies` boxes (6 dofs each), `perInterface` contacts between box i - 1 and box i
// (the ground below box 0): W = G M^-1 G^T is block-tridiagonal in body order and rank-deficient
// (12 rows per interface for 6 dofs), like the 20-box tower's.
BlockSparseMatrix towerDelassus(int bodies, int perInterface, unsigned seed,
                                Eigen::VectorXd* velocity = nullptr) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> g(0.0, 1.0);
  const int contacts = bodies * perInterface, n = 3 * contacts, dofs = 6 * bodies;
  Eigen::MatrixXd G = Eigen::MatrixXd::Zero(n, dofs);
  for (int c = 0; c < contacts; ++c) {
    const int upper = c / perInterface;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 6; ++j) {
        G(3 * c + i, 6 * upper + j) = g(rng);
        if (upper > 0) G(3 * c + i, 6 * (upper - 1) + j) = -g(rng);
      }
  }
  Eigen::VectorXd invMass(dofs);
  for (int j = 0; j < dofs; ++j) invMass[j] = 0.5 + std::abs(g(rng));
  Eigen::MatrixXd W = G * invMass.asDiagonal() * G.transpose();
  W = 0.5 * (W + W.transpose());
  if (velocity) {  // q = G v for a random body velocity v: in range(G), so a solution exists
    Eigen::VectorXd v(dofs);
    for (auto& x : v) x = g(rng);
    *velocity = G * v;
  }
  return DelassusOperator::dense(W).toBlockSparse(std::vector<int>(contacts, 3));
}

std::vector<NewtonBlockJacobian> randomJacobian(int blocks, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> g(0.0, 1.0);
  std::vector<NewtonBlockJacobian> jac(blocks);
  for (auto& j : jac) {
    for (int a = 0; a < 3; ++a)
      for (int c = 0; c < 3; ++c) {
        j.A(a, c) = (a == c ? 1.0 : 0.0) + 0.3 * g(rng);
        j.B(a, c) = (a == c ? 0.5 : 0.0) + 0.1 * g(rng);
      }
  }
  return jac;
}

// Makes row `row` a unit row (A_i = 0, B_i = e_i): it is eliminated from J_RR.
void makeUnitRow(std::vector<NewtonBlockJacobian>& jac, int row) {
  NewtonBlockJacobian& j = jac[row / 3];
  j.A.row(row % 3).setZero();
  j.B.row(row % 3).setZero();
  j.B(row % 3, row % 3) = 1.0;
}

struct Rows {
  std::vector<int> kept, index;
};

Rows keptRows(const std::vector<NewtonBlockJacobian>& jac, int n) {
  Rows r;
  r.index.assign(n, -1);
  for (int i = 0; i < n; ++i) {
    const NewtonBlockJacobian& j = jac[i / 3];
    bool unit = true;
    for (int t = 0; t < 3; ++t)
      unit = unit && j.A(i % 3, t) == 0.0 && j.B(i % 3, t) == (t == i % 3 ? 1.0 : 0.0);
    if (unit) continue;
    r.index[i] = static_cast<int>(r.kept.size());
    r.kept.push_back(i);
  }
  return r;
}

// The reference: J = A (W + sigma I) + B formed densely, restricted to R, solved by full-pivoting
// LU (independent of the solver's assembly).
Eigen::VectorXd referenceStep(const BlockSparseMatrix& W,
                              const std::vector<NewtonBlockJacobian>& jac, const Rows& rows,
                              double sigma, const Eigen::VectorXd& rhs) {
  const int n = W.size();
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(n, n), B = Eigen::MatrixXd::Zero(n, n);
  for (int b = 0; b < W.blockCount(); ++b) {
    A.block<3, 3>(3 * b, 3 * b) = jac[b].A;
    B.block<3, 3>(3 * b, 3 * b) = jac[b].B;
  }
  const Eigen::MatrixXd J = A * (W.toDense() + sigma * Eigen::MatrixXd::Identity(n, n)) + B;
  const int m = static_cast<int>(rows.kept.size());
  Eigen::MatrixXd JRR(m, m);
  for (int i = 0; i < m; ++i)
    for (int k = 0; k < m; ++k) JRR(i, k) = J(rows.kept[i], rows.kept[k]);
  return JRR.fullPivLu().solve(rhs);
}

std::vector<int> offsets(const BlockSparseMatrix& W) {
  std::vector<int> o(W.blockCount() + 1);
  for (int b = 0; b <= W.blockCount(); ++b) o[b] = 3 * b;
  return o;
}

double relativeError(const Eigen::VectorXd& x, const Eigen::VectorXd& ref) {
  return (x - ref).norm() / ref.norm();
}

}  // namespace

// The sparse path (any size above the threshold) and the dense LU give the same Newton step on
// a 20-box tower (240 unknowns, some rows eliminated) as a dense full-pivoting reference.
TEST(NewtonLinearSolver, SparseAndDenseGiveTheSameStepOnATower) {
  const BlockSparseMatrix W = towerDelassus(20, 4, 3);
  ASSERT_EQ(W.size(), 240);
  ASSERT_LT(W.nonZeroBlocks(), 80 * 80 / 4);  // block-tridiagonal, not dense
  const std::vector<int> offset = offsets(W);
  for (unsigned seed = 1; seed <= 5; ++seed) {
    std::vector<NewtonBlockJacobian> jac = randomJacobian(W.blockCount(), seed);
    for (int i = static_cast<int>(seed); i < W.size(); i += 17) makeUnitRow(jac, i);
    const Rows rows = keptRows(jac, W.size());
    ASSERT_LT(rows.kept.size(), 240u);
    const double sigma = 1e-6 * seed;
    std::mt19937 rng(seed);
    std::normal_distribution<double> g(0.0, 1.0);
    Eigen::VectorXd rhs(rows.kept.size());
    for (auto& v : rhs) v = g(rng);
    const Eigen::VectorXd ref = referenceStep(W, jac, rows, sigma, rhs);
    NewtonLinearSolver dense(1000), sparse(0, 1.0);
    Eigen::VectorXd xd, xs;
    ASSERT_TRUE(dense.solve(W, offset, jac, rows.kept, rows.index, sigma, rhs, xd));
    ASSERT_TRUE(sparse.solve(W, offset, jac, rows.kept, rows.index, sigma, rhs, xs));
    EXPECT_EQ(dense.stats().denseSolves, 1);
    EXPECT_EQ(dense.stats().sparseSolves, 0);
    EXPECT_EQ(sparse.stats().sparseSolves, 1);
    EXPECT_EQ(sparse.stats().denseSolves, 0);
    EXPECT_LT(relativeError(xd, ref), 1e-10) << seed;
    EXPECT_LT(relativeError(xs, ref), 1e-10) << seed;
    EXPECT_LT(relativeError(xs, xd), 1e-10) << seed;
  }
}

// The default rule: a 30-box tower (360 rows, W ~9 % full) goes sparse, a dense W of 240 rows
// (one body under 80 contacts) and a 60-row tower stay with the dense LU.
TEST(NewtonLinearSolver, DefaultRuleUsesSparseOnlyForLargeSparseW) {
  auto run = [](const BlockSparseMatrix& W) {
    std::vector<NewtonBlockJacobian> jac = randomJacobian(W.blockCount(), 3);
    const Rows rows = keptRows(jac, W.size());
    const Eigen::VectorXd rhs = Eigen::VectorXd::Ones(W.size());
    NewtonSettings defaults;
    NewtonLinearSolver solver(defaults.denseThreshold, defaults.sparseMaxDensity);
    Eigen::VectorXd x;
    EXPECT_TRUE(solver.solve(W, offsets(W), jac, rows.kept, rows.index, 1e-6, rhs, x));
    EXPECT_LT(relativeError(x, referenceStep(W, jac, rows, 1e-6, rhs)), 1e-10);
    return solver.stats();
  };
  EXPECT_EQ(run(towerDelassus(30, 4, 3)).sparseSolves, 1);
  EXPECT_EQ(run(towerDelassus(1, 80, 3)).denseSolves, 1);
  EXPECT_EQ(run(towerDelassus(5, 4, 3)).denseSolves, 1);
}

// Same kept rows: the pattern and the symbolic analysis are reused with new values (and the step
// is still exact); other kept rows: they are rebuilt.
TEST(NewtonLinearSolver, PatternIsReusedForTheSameRowsAndRebuiltForOthers) {
  const BlockSparseMatrix W = towerDelassus(12, 4, 5);
  const std::vector<int> offset = offsets(W);
  NewtonLinearSolver solver(0, 1.0);
  Eigen::VectorXd x;
  auto check = [&](const std::vector<NewtonBlockJacobian>& jac, double sigma, unsigned seed) {
    const Rows rows = keptRows(jac, W.size());
    Eigen::VectorXd rhs =
        Eigen::VectorXd::LinSpaced(static_cast<int>(rows.kept.size()), -1.0, 1.0 + seed);
    ASSERT_TRUE(solver.solve(W, offset, jac, rows.kept, rows.index, sigma, rhs, x));
    EXPECT_LT(relativeError(x, referenceStep(W, jac, rows, sigma, rhs)), 1e-10) << seed;
  };
  std::vector<NewtonBlockJacobian> jac1 = randomJacobian(W.blockCount(), 11);
  makeUnitRow(jac1, 7);
  check(jac1, 1e-8, 1);
  EXPECT_EQ(solver.stats().patternAnalyses, 1);
  EXPECT_FALSE(solver.stats().lastReusedPattern);

  std::vector<NewtonBlockJacobian> jac2 = randomJacobian(W.blockCount(), 12);  // new values
  makeUnitRow(jac2, 7);
  check(jac2, 1e-5, 2);
  EXPECT_EQ(solver.stats().patternAnalyses, 1);
  EXPECT_TRUE(solver.stats().lastReusedPattern);

  std::vector<NewtonBlockJacobian> jac3 = jac2;  // one more row eliminated
  makeUnitRow(jac3, 40);
  check(jac3, 1e-5, 3);
  EXPECT_EQ(solver.stats().patternAnalyses, 2);
  EXPECT_FALSE(solver.stats().lastReusedPattern);

  check(jac2, 1e-6, 4);  // back to the first rows: only the last pattern is kept
  EXPECT_EQ(solver.stats().patternAnalyses, 3);
  EXPECT_FALSE(solver.stats().lastReusedPattern);
  check(jac1, 1e-6, 5);
  EXPECT_EQ(solver.stats().patternAnalyses, 3);
  EXPECT_TRUE(solver.stats().lastReusedPattern);
  EXPECT_EQ(solver.stats().sparseSolves, 5);

  // Another W with the same structure (other values): reused; another structure of the same
  // size (6 boxes under 8 contacts each): rebuilt.
  const Rows rows = keptRows(jac1, W.size());
  const Eigen::VectorXd rhs = Eigen::VectorXd::Ones(static_cast<int>(rows.kept.size()));
  const BlockSparseMatrix same = towerDelassus(12, 4, 6);
  ASSERT_TRUE(solver.solve(same, offset, jac1, rows.kept, rows.index, 1e-6, rhs, x));
  EXPECT_EQ(solver.stats().patternAnalyses, 3);
  EXPECT_TRUE(solver.stats().lastReusedPattern);
  EXPECT_LT(relativeError(x, referenceStep(same, jac1, rows, 1e-6, rhs)), 1e-10);
  const BlockSparseMatrix other = towerDelassus(6, 8, 6);
  ASSERT_EQ(other.size(), W.size());
  ASSERT_TRUE(solver.solve(other, offset, jac1, rows.kept, rows.index, 1e-6, rhs, x));
  EXPECT_EQ(solver.stats().patternAnalyses, 4);
  EXPECT_FALSE(solver.stats().lastReusedPattern);
  EXPECT_LT(relativeError(x, referenceStep(other, jac1, rows, 1e-6, rhs)), 1e-10);
}

// A singular J_RR (sigma = 0, B = 0, W rank-deficient) is reported, not returned as a step.
TEST(NewtonLinearSolver, SingularSystemIsReported) {
  const BlockSparseMatrix W = towerDelassus(6, 4, 9);  // 72 rows, rank <= 36
  const std::vector<int> offset = offsets(W);
  std::vector<NewtonBlockJacobian> jac(W.blockCount());
  for (auto& j : jac) j.A.setIdentity();
  const Rows rows = keptRows(jac, W.size());
  const Eigen::VectorXd rhs = Eigen::VectorXd::Ones(W.size());
  Eigen::VectorXd x;
  EXPECT_FALSE(
      NewtonLinearSolver(0, 1.0).solve(W, offset, jac, rows.kept, rows.index, 0.0, rhs, x));
  EXPECT_FALSE(NewtonLinearSolver(1000).solve(W, offset, jac, rows.kept, rows.index, 0.0, rhs, x));
}

// Whole Newton solves on a tower-like problem: the sparse path reaches the dense path's answer.
TEST(NewtonLinearSolver, NewtonOnATowerAgreesBetweenSparseAndDense) {
  Eigen::VectorXd q;
  const BlockSparseMatrix W = towerDelassus(10, 4, 21, &q);
  const ContactProblem problem = ContactProblem::contacts(
      DelassusOperator::blockSparse(W), q, std::vector<double>(W.blockCount(), 0.5), "tower");
  const PreparedProblem pp = PreparedProblem::from(problem);
  SolverOptions o;
  o.tolerance = 1e-10;
  const SolveContext c(o, SolveContext::Clock::now());
  NewtonSettings dense, sparse;
  dense.denseThreshold = 1000;
  sparse.denseThreshold = 0;
  sparse.sparseMaxDensity = 1.0;
  Eigen::VectorXd r1 = Eigen::VectorXd::Zero(pp.size()), r2 = r1;
  SolverReport a, b;
  runNonsmoothNewton(pp, AlartCurnierFunction{}, dense, c, 200, r1, a);
  runNonsmoothNewton(pp, AlartCurnierFunction{}, sparse, c, 200, r2, b);
  EXPECT_EQ(a.status, SolverStatus::Converged) << a.message;
  EXPECT_EQ(b.status, SolverStatus::Converged) << b.message;
  EXPECT_EQ(a.iterations, b.iterations);
  Eigen::VectorXd u1, u2;  // r is not unique (W singular), u = W r + q is compared
  pp.velocity(r1, u1);
  pp.velocity(r2, u2);
  EXPECT_LT((u1 - u2).norm(), 1e-8 * (1 + u1.norm()));
  EXPECT_LT((r1 - r2).norm(), 1e-6 * (1 + r1.norm()));
}

// New values on the same pattern are factored on the last factorization's pivots (KLU's
// refactorization); where those pivots no longer serve (here: every one of them is zero), the
// solve misses its accuracy check and a fresh factorization with a pivot search takes over.
TEST(NewtonLinearSolver, RefactorsOnTheKeptPivotsAndFactorsAfreshWhenTheyFail) {
  // Two contacts coupled through every entry: W's pattern is all four 3 x 3 blocks.
  auto twoContacts = [](const Eigen::MatrixXd& dense) {
    return DelassusOperator::dense(dense).toBlockSparse(std::vector<int>(2, 3));
  };
  Eigen::MatrixXd first = Eigen::MatrixXd::Constant(6, 6, 0.5);
  first.diagonal().setConstant(4.0);  // diagonally dominant: the pivots are the diagonal
  Eigen::MatrixXd slightly = first;
  slightly(0, 1) += 0.1;
  slightly(4, 4) -= 0.2;
  Eigen::MatrixXd swapped = Eigen::MatrixXd::Zero(6, 6);  // [0 I; I 0]: zero diagonal
  swapped.topRightCorner(3, 3).setIdentity();
  swapped.bottomLeftCorner(3, 3).setIdentity();
  std::vector<NewtonBlockJacobian> jac(2);
  for (auto& j : jac) j.A.setIdentity();  // J = A W + B = W on every row
  const Rows rows = keptRows(jac, 6);
  ASSERT_EQ(rows.kept.size(), 6u);
  const Eigen::VectorXd rhs = Eigen::VectorXd::LinSpaced(6, -1.0, 2.0);
  NewtonLinearSolver solver(0, 1.0);  // sparse at any size
  Eigen::VectorXd x;
  for (const Eigen::MatrixXd* values : {&first, &slightly, &swapped}) {
    const BlockSparseMatrix W = twoContacts(*values);
    ASSERT_TRUE(solver.solve(W, offsets(W), jac, rows.kept, rows.index, 0.0, rhs, x));
    EXPECT_LT((*values * x - rhs).norm(), 1e-12 * rhs.norm());
  }
  EXPECT_EQ(solver.stats().patternAnalyses, 1);
  EXPECT_EQ(solver.stats().sparseSolves, 3);
  EXPECT_EQ(solver.stats().refactorFallbacks, 1);  // the swapped matrix only
}
