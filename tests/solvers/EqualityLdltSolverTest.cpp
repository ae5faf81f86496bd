// solvers/direct/EqualityLdltSolver: equality-only problems solved by one sparse LDL^T.
#include <gtest/gtest.h>
#include <coulomb/solvers/SolveWithFallback.hpp>
#include <coulomb/solvers/SolverChooser.hpp>
#include <coulomb/solvers/direct/EqualityLdltSolver.hpp>

#include <Eigen/Cholesky>

using namespace coulomb::solvers;

namespace {

// The W of a chain of n unit point masses joined by scalar rows: tridiagonal, 2 on the diagonal,
// -1 beside it (a tree: no fill-in), every row an equality.
ContactProblem chainProblem(int n, bool dense) {
  Eigen::MatrixXd W = Eigen::MatrixXd::Zero(n, n);
  for (int i = 0; i < n; ++i) {
    W(i, i) = 2.0;
    if (i + 1 < n) W(i, i + 1) = W(i + 1, i) = -1.0;
  }
  ContactProblem p;
  p.name = "chain";
  p.q = Eigen::VectorXd::LinSpaced(n, -1.0, 2.0);
  p.blocks.assign(n, ConstraintBlock::equality());
  if (dense) {
    p.W = DelassusOperator::dense(W);
  } else {
    std::vector<MatrixBlockEntry> entries;
    for (int i = 0; i < n; ++i)
      for (int j = std::max(0, i - 1); j <= std::min(n - 1, i + 1); ++j)
        entries.push_back({i, j, {W(i, j)}});
    p.W = DelassusOperator::blockSparse(BlockSparseMatrix(std::vector<int>(n, 1), entries));
  }
  return p;
}

}  // namespace

TEST(EqualityLdltSolver, SolvesTheLinearSystemInOneStep) {
  for (const bool dense : {true, false}) {
    const ContactProblem p = chainProblem(200, dense);
    const SolveOutcome out = EqualityLdltSolver().solve(p, {});
    EXPECT_EQ(out.report.status, SolverStatus::Converged) << out.report.message;
    EXPECT_EQ(out.report.iterations, 1);
    EXPECT_LT(out.report.residual, 1e-12);
    // u = W r + q = 0 for every row, against a dense reference solve.
    const Eigen::MatrixXd W = p.W.toBlockSparse(p.blockSizes()).toDense();
    const Eigen::VectorXd reference = W.ldlt().solve(-p.q);
    EXPECT_LT((out.impulses - reference).norm(), 1e-9 * reference.norm());
    EXPECT_LT(out.velocities.norm(), 1e-9);
  }
}

TEST(EqualityLdltSolver, OnlyEqualityRows) {
  ContactProblem p = chainProblem(3, true);
  p.blocks[1] = ConstraintBlock::unilateral();
  const SolveOutcome out = EqualityLdltSolver().solve(p, {});
  EXPECT_EQ(out.report.status, SolverStatus::NotApplicable);
  EXPECT_NE(out.report.message.find("equality rows only"), std::string::npos);
}

TEST(EqualityLdltSolver, ARedundantRowFallsBackToNewton) {
  // Two identical rows (a loop closed twice): W singular, r not unique; q consistent.
  Eigen::MatrixXd W(3, 3);
  W << 2, 2, -1, 2, 2, -1, -1, -1, 2;
  ContactProblem p;
  p.W = DelassusOperator::dense(W);
  p.q = Eigen::Vector3d(1.0, 1.0, -0.5);
  p.blocks.assign(3, ConstraintBlock::equality());
  const SolvePlan plan =
      SolverChooser().choose(p, {}, SolverChoice::automatic(), SolvePolicy::simulationOptions());
  EXPECT_EQ(plan.rule, PlanRule::EqualityRowsOnly);
  ASSERT_GE(plan.attempts.size(), 2u);
  EXPECT_EQ(plan.attempts[0].solver, "ldlt");
  EXPECT_EQ(plan.attempts[1].solver, "ac_newton");
  const PlanOutcome out = solveWithFallback(p, plan, SolverRegistry::builtIn());
  EXPECT_TRUE(out.converged()) << out.best.report.message;
  EXPECT_LE(out.best.report.residual, 1e-6);
  EXPECT_TRUE(out.best.impulses.allFinite());
}

TEST(EqualityLdltSolver, RowsInThreesAreSolvedByBlocksAsByEntries) {
  // A chain of 30 ball joints: rows in threes, joint g coupled with g - 1 and g + 1 by 3 x 3
  // blocks (W symmetric positive definite); the block path must give the dense answer, and so
  // must the entry path on the same chain with a 91st row appended (91 rows: not in threes).
  const auto chainOfBallJoints = [](int rows) {
    const int joints = 30;
    Eigen::MatrixXd W = Eigen::MatrixXd::Zero(rows, rows);
    for (int g = 0; g < joints; ++g) {
      W.block<3, 3>(3 * g, 3 * g) = Eigen::Matrix3d::Identity() * 4.0;
      W(3 * g, 3 * g + 1) = W(3 * g + 1, 3 * g) = 0.5;
      if (g + 1 < joints) {
        Eigen::Matrix3d c;
        c << -1.0, 0.2, 0.0, 0.1, -1.0, 0.3, 0.0, -0.2, -1.0;
        W.block<3, 3>(3 * g + 3, 3 * g) = c;
        W.block<3, 3>(3 * g, 3 * g + 3) = c.transpose();
      }
    }
    if (rows > 3 * joints) {  // one more row, coupled to the last joint's first row
      W(rows - 1, rows - 1) = 3.0;
      W(rows - 1, 3 * joints - 3) = W(3 * joints - 3, rows - 1) = 0.5;
    }
    std::vector<MatrixBlockEntry> entries;
    for (int i = 0; i < rows; ++i)
      for (int j = 0; j < rows; ++j)
        if (W(i, j) != 0.0 || (i < 3 * joints && j < 3 * joints && std::abs(i / 3 - j / 3) <= 1))
          entries.push_back({i, j, {W(i, j)}});  // whole 3 x 3 blocks, their zeros included
    ContactProblem p;
    p.name = "ball joints";
    p.q = Eigen::VectorXd::LinSpaced(rows, -1.0, 2.0);
    p.blocks.assign(rows, ConstraintBlock::equality());
    p.W = DelassusOperator::blockSparse(BlockSparseMatrix(std::vector<int>(rows, 1), entries));
    return std::pair{p, W};
  };
  for (const int rows : {90, 91}) {
    const auto [p, W] = chainOfBallJoints(rows);
    const SolveOutcome out = EqualityLdltSolver().solve(p, {});
    EXPECT_EQ(out.report.status, SolverStatus::Converged) << out.report.message;
    const Eigen::VectorXd reference = W.ldlt().solve(-p.q);
    EXPECT_LT((out.impulses - reference).norm(), 1e-12 * reference.norm()) << rows << " rows";
  }
}

TEST(EqualityLdltSolver, BodySpaceRowsInThreesAreSolvedFromTheFactors) {
  // A chain of 40 ball joints in body space (as the assembler gives an island above its explicit
  // row limit): joint g joins body g - 1 (the world for g = 0) and body g, three 1-row blocks on
  // the same bodies. The blocks formed from J and M^-1 J^T must give the dense answer; so must
  // the entry path when one row of the last joint is moved onto other bodies (no longer threes).
  const int joints = 40;
  for (const bool broken : {false, true}) {
    auto factors = std::make_shared<BodySpaceDelassus>(joints, std::vector<int>(3 * joints, 1));
    std::srand(3);
    std::vector<Eigen::Matrix<double, 6, 6>> inverseMass(joints);
    for (int b = 0; b < joints; ++b) {
      const Eigen::Matrix<double, 6, 6> a = Eigen::Matrix<double, 6, 6>::Random();
      inverseMass[b] = a * a.transpose() + Eigen::Matrix<double, 6, 6>::Identity();
    }
    for (int g = 0; g < joints; ++g)
      for (int a = 0; a < 3; ++a) {
        const int row = 3 * g + a;
        const bool moved = broken && g == joints - 1 && a == 2;
        const int bodyA = moved ? 0 : g - 1, bodyB = moved ? 1 : g;
        for (int side = 0; side < 2; ++side) {
          const int body = side == 0 ? bodyA : bodyB;
          if (body < 0) continue;
          const Eigen::Matrix<double, 1, 6> J = Eigen::Matrix<double, 1, 6>::Random();
          const Eigen::Matrix<double, 6, 1> G = inverseMass[body] * J.transpose();
          factors->setSide(row, side, body, J, G);
        }
      }
    ContactProblem p;
    p.name = "ball joints, body space";
    p.q = Eigen::VectorXd::LinSpaced(3 * joints, -1.0, 2.0);
    p.blocks.assign(3 * joints, ConstraintBlock::equality());
    p.W = DelassusOperator::bodySpace(factors);
    const SolveOutcome out = EqualityLdltSolver().solve(p, {});
    EXPECT_EQ(out.report.status, SolverStatus::Converged) << out.report.message;
    const Eigen::MatrixXd W = p.W.toBlockSparse(p.blockSizes()).toDense();
    const Eigen::VectorXd reference = W.ldlt().solve(-p.q);
    EXPECT_LT((out.impulses - reference).norm(), 1e-10 * reference.norm())
        << (broken ? "entries" : "blocks");
  }
}
