#include <gtest/gtest.h>
#include <coulomb/solvers/lemke/LemkeSolver.hpp>

#include "TestProblems.hpp"

#include <cmath>

using namespace coulomb::solvers;

namespace {
constexpr double kPi = 3.14159265358979323846;
}

// docs/solver-derivations.md (7.4), one contact, W = I, mu = 0.5, n_d = 8.
TEST(LemkeSolver, SingleContactTakeOffAndStickAreExact) {
  const Eigen::Matrix3d W = Eigen::Matrix3d::Identity();
  SolveOutcome out = LemkeSolver().solve(fixtures::singleContact(W, {0.3, 1, -2}, 0.5));
  EXPECT_EQ(out.report.status, SolverStatus::Converged);
  EXPECT_LT(out.impulses.norm(), 1e-14);
  out = LemkeSolver().solve(fixtures::singleContact(W, {-1, 0.2, -0.1}, 0.5));
  EXPECT_EQ(out.report.status, SolverStatus::Converged) << out.report.message;
  EXPECT_LT((out.impulses - Eigen::Vector3d(1, -0.2, 0.1)).norm(), 1e-12);
}

TEST(LemkeSolver, SlidingAlongAFacetIsExact) {
  const SolveOutcome out =
      LemkeSolver().solve(fixtures::singleContact(Eigen::Matrix3d::Identity(), {-1, 2, 0}, 0.5));
  EXPECT_EQ(out.report.status, SolverStatus::Converged) << out.report.message;
  EXPECT_NEAR(out.impulses[1], -0.5, 1e-12);
}

// Sliding between two facets (22.5 degrees): the friction snaps to the polygon, its magnitude
// is cos(pi/8) mu r_N, and the report shows the cone error next to an exact LCP.
TEST(LemkeSolver, SlidingBetweenFacetsShowsTheConeError) {
  const double a = kPi / 8;
  const SolveOutcome out = LemkeSolver().solve(fixtures::singleContact(
      Eigen::Matrix3d::Identity(), {-1, 2 * std::cos(a), 2 * std::sin(a)}, 0.5));
  EXPECT_EQ(out.report.status, SolverStatus::Stalled);  // not converged on the exact cone
  EXPECT_LT(out.report.nativeResidual, 1e-14);          // but the faceted LCP is solved
  EXPECT_GT(out.report.residual, 1e-3);                 // and the exact-cone error is visible
  const double friction = std::hypot(out.impulses[1], out.impulses[2]);
  EXPECT_NEAR(friction / (0.5 * out.impulses[0]), std::cos(kPi / 8), 1e-9);
  EXPECT_NE(out.report.message.find("faceted"), std::string::npos) << out.report.message;
  // finer polygons shrink the error (proportional to n_d^-2)
  LemkeOptions fine;
  fine.frictionDirections = 32;
  const SolveOutcome outFine = LemkeSolver(fine).solve(fixtures::singleContact(
      Eigen::Matrix3d::Identity(), {-1, 2 * std::cos(a), 2 * std::sin(a)}, 0.5));
  EXPECT_LT(outFine.report.residual, out.report.residual / 8);
}

// A body squeezed between two opposite contacts that both demand separation (bias on a null
// direction of W, docs/solver-derivations.md (7.7)): the ray is reported as a status with the
// reason.
TEST(LemkeSolver, SqueezedBodyWithBiasEndsOnARay) {
  Eigen::MatrixXd J = Eigen::MatrixXd::Zero(6, 3);  // one body, 3 translational dofs
  J(0, 0) = 1;                                      // contact 1 normal +x
  J(1, 1) = 1;                                      // tangents
  J(2, 2) = 1;
  J(3, 0) = -1;  // contact 2 normal -x
  J(4, 1) = 1;
  J(5, 2) = 1;
  const Eigen::MatrixXd W = J * J.transpose();
  Eigen::VectorXd q = Eigen::VectorXd::Zero(6);
  ContactProblem noBias = ContactProblem::contacts(DelassusOperator::dense(W), q, {0.3, 0.3});
  EXPECT_EQ(LemkeSolver().solve(noBias).report.status, SolverStatus::Converged);
  q[0] = q[3] = -0.1;  // both ask for separation: impossible
  const ContactProblem biased = ContactProblem::contacts(DelassusOperator::dense(W), q, {0.3, 0.3});
  const SolveOutcome out = LemkeSolver().solve(biased);
  EXPECT_EQ(out.report.status, SolverStatus::Stalled);
  EXPECT_NE(out.report.message.find("RAY TERMINATION"), std::string::npos) << out.report.message;
  EXPECT_TRUE(out.impulses.allFinite());
}

TEST(LemkeSolver, EqualityAndBoundedRows) {
  // W = 2 I (5 x 5): a contact (stick), an equality row, a bounded row hitting its bound.
  const Eigen::MatrixXd W = 2.0 * Eigen::MatrixXd::Identity(5, 5);
  ContactProblem p;
  p.W = DelassusOperator::dense(W);
  p.q = (Eigen::VectorXd(5) << -2, 0.2, 0.0, 1.0, -4.0).finished();
  p.blocks = {ConstraintBlock::contact(0.5), ConstraintBlock::equality(),
              ConstraintBlock::bounded(-0.5, 0.5)};
  const SolveOutcome out = LemkeSolver().solve(p);
  EXPECT_EQ(out.report.status, SolverStatus::Converged) << out.report.message;
  EXPECT_NEAR(out.impulses[0], 1.0, 1e-9);   // stick: u = 0
  EXPECT_NEAR(out.impulses[3], -0.5, 1e-9);  // equality: 2 r + 1 = 0
  EXPECT_NEAR(out.impulses[4], 0.5, 1e-9);   // wants 2, clamped to the upper bound
}

TEST(LemkeSolver, CorpusFixturesPivotToAnLcpSolution) {
  for (const char* name : fixtures::kFixtures) {
    const SolveOutcome out = LemkeSolver().solve(fixtures::loadFixture(name));
    EXPECT_LT(out.report.nativeResidual, 1e-10) << name << ": " << out.report.message;
    EXPECT_NE(out.report.status, SolverStatus::MaxIterations) << name;
  }
}

// Redundant contacts (issue 24 item 4): a box stack with four coplanar points per face (52
// contacts, W of rank 78 / 156) and a periodic box of polyhedra (60 contacts, W of order 1e-4, q
// with a component on the null space of W). The degenerate path ended on spurious rays (residuals
// 4.4e-9 and 4.3e-3); nothing slides, so the faceted LCP solution is exact on the cone too.
TEST(LemkeSolver, RedundantContactsEndSolved) {
  for (const char* name :
       {"redundant/BoxesStack1-i100000-32", "redundant/LMGC_100_PR_PerioBox-i00361-60-03000"}) {
    const SolveOutcome out = LemkeSolver().solve(fixtures::loadFixture(name));
    EXPECT_EQ(out.report.status, SolverStatus::Converged) << name << ": " << out.report.message;
    EXPECT_LE(out.report.residual, 1e-10) << name << ": " << out.report.message;
    EXPECT_EQ(out.report.message.find("RAY"), std::string::npos) << name;
  }
}

// A 40-contact box stack captured from a simulation under lemke!: a pivot of 5.9e-10 that was
// rounding noise sent the path to an infeasible basis and cycling (pivot limit, 4000 pivots)
// before small pivots were checked on a fresh tableau.
TEST(LemkeSolver, NoisyPivotsAreCheckedOnAFreshTableau) {
  const ContactProblem p = fixtures::loadFixture("redundant/box_stack_10_step1446_island0");
  const SolveOutcome out = LemkeSolver().solve(p);
  EXPECT_EQ(out.report.status, SolverStatus::Converged) << out.report.message;
  EXPECT_LE(out.report.residual, 1e-9) << out.report.message;
  EXPECT_LT(out.report.iterations, 400);
}

// The same tower at steps 134 (the checked path cycles) and 824 (it ends "solved" at an LCP error
// of 2e-3): the plain path solves both, so solveLcpLemke follows it when the first path ends
// without an accurate solution.
TEST(LemkeSolver, APathThatFailsIsFollowedByThePlainPath) {
  for (const char* name :
       {"redundant/box_stack_10_step134_island0", "redundant/box_stack_10_step824_island0"}) {
    const SolveOutcome out = LemkeSolver().solve(fixtures::loadFixture(name));
    EXPECT_EQ(out.report.status, SolverStatus::Converged) << name << ": " << out.report.message;
    EXPECT_LE(out.report.residual, 1e-9) << name << ": " << out.report.message;
    EXPECT_LT(out.report.iterations, 1000) << name;  // at most 800 checked pivots + the plain path
  }
}

// The answer does not depend on the units of W: the same stack with W and q scaled by 1e-6 and
// 1e6 (r unchanged) is solved the same way (the LCP is built from W / max diag W).
TEST(LemkeSolver, UnitsOfWDoNotMatter) {
  const ContactProblem base = fixtures::loadFixture("redundant/BoxesStack1-i100000-32");
  const SolveOutcome ref = LemkeSolver().solve(base);
  const Eigen::MatrixXd W = base.W.toBlockSparse(std::vector<int>(base.size() / 3, 3)).toDense();
  for (const double k : {1e-6, 1e6}) {
    ContactProblem p = base;
    p.W = DelassusOperator::dense(k * W);
    p.q = k * base.q;
    const SolveOutcome out = LemkeSolver().solve(p);
    EXPECT_EQ(out.report.status, SolverStatus::Converged) << k << ": " << out.report.message;
    EXPECT_EQ(out.report.iterations, ref.report.iterations) << k;
    EXPECT_LT((out.impulses - ref.impulses).lpNorm<Eigen::Infinity>(),
              1e-8 * ref.impulses.lpNorm<Eigen::Infinity>())
        << k;
  }
}

// The common iteration cap (the World's is 200 sweeps) never cuts a pivoting path short: a basis
// with z0 still in it is no answer (applied, it shot bodies away, issue 24 item 4).
TEST(LemkeSolver, TheIterationCapDoesNotCutThePathShort) {
  SolverOptions capped;
  capped.maxIterations = 20;  // BoxesStack needs about 115 pivots
  const SolveOutcome out =
      LemkeSolver().solve(fixtures::loadFixture("redundant/BoxesStack1-i100000-32"), capped);
  EXPECT_EQ(out.report.status, SolverStatus::Converged) << out.report.message;
  EXPECT_GT(out.report.iterations, 20);
}

TEST(LemkeSolver, TooLargeIsNotApplicable) {
  LemkeOptions small;
  small.maxLcpSize = 20;
  const SolveOutcome out = LemkeSolver(small).solve(fixtures::randomMechanical(5, 30, 0.5, 1));
  EXPECT_EQ(out.report.status, SolverStatus::NotApplicable);
}
