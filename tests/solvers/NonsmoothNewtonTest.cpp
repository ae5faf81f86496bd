#include <gtest/gtest.h>
#include <coulomb/solvers/newton/NonsmoothNewton.hpp>

#include "TestProblems.hpp"

using namespace coulomb::solvers;

namespace {
SolverReport run(const ContactProblem& p, const NewtonSettings& s, double tol, Eigen::VectorXd& r) {
  const PreparedProblem pp = PreparedProblem::from(p);
  SolverOptions o;
  o.tolerance = tol;
  const SolveContext c(o, SolveContext::Clock::now());
  r = Eigen::VectorXd::Zero(pp.size());
  SolverReport report;
  runNonsmoothNewton(pp, AlartCurnierFunction{}, s, c, 200, r, report);
  return report;
}
}  // namespace

// Issue 5 item 8: random well-posed problems (nu = 3n/m < 1) to 1e-10 in few iterations.
TEST(NonsmoothNewton, RandomWellPosedProblemsConvergeFast) {
  for (unsigned seed = 1; seed <= 20; ++seed) {
    const ContactProblem p = fixtures::randomMechanical(4 + seed % 5, 40, 0.2 + 0.05 * seed, seed);
    Eigen::VectorXd r;
    const SolverReport rep = run(p, NewtonSettings{}, 1e-10, r);
    EXPECT_EQ(rep.status, SolverStatus::Converged) << seed << " " << rep.message;
    EXPECT_LE(rep.iterations, 25) << seed;
  }
}

TEST(NonsmoothNewton, SparsePathAndRowEliminationAgreeWithDense) {
  const ContactProblem p = fixtures::randomMechanical(12, 60, 0.5, 77);
  NewtonSettings dense, sparse;
  sparse.denseThreshold = 0;
  sparse.sparseMaxDensity = 1.0;  // W is dense here: force the sparse LU
  Eigen::VectorXd r1, r2;
  const SolverReport a = run(p, dense, 1e-11, r1), b = run(p, sparse, 1e-11, r2);
  EXPECT_EQ(a.status, SolverStatus::Converged);
  EXPECT_EQ(b.status, SolverStatus::Converged);
  EXPECT_LT((r1 - r2).norm(), 1e-8 * (1 + r1.norm()));
}

TEST(NonsmoothNewton, RedundantContactsNeedTheShift) {
  // nu = 2.4: W singular; the shift (5.8) keeps the Newton systems solvable.
  const ContactProblem p = fixtures::randomMechanical(8, 10, 0.3, 4);
  Eigen::VectorXd r;
  const SolverReport rep = run(p, NewtonSettings{}, 1e-9, r);
  EXPECT_TRUE(r.allFinite());
  EXPECT_GT(rep.maxRegularization, 0.0);
  EXPECT_EQ(rep.status, SolverStatus::Converged) << rep.message;
}
