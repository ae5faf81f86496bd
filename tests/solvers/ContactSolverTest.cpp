// The solve() contract, checked for every registered solver: analytic single-contact cases to
// 1e-12, invalid problems, empty problems, warm starts, no NaN.
#include <gtest/gtest.h>
#include <coulomb/solvers/ContactSolver.hpp>
#include <coulomb/solvers/Residual.hpp>
#include <coulomb/solvers/SolverRegistry.hpp>

#include <limits>

#include "TestProblems.hpp"

using namespace coulomb::solvers;

namespace {

struct Analytic {
  const char* name;
  Eigen::Matrix3d W;
  Eigen::Vector3d q;
  double mu;
  Eigen::Vector3d r;
};

std::vector<Analytic> analyticCases() {
  Eigen::Matrix3d spd;
  spd << 2.0, 0.3, -0.2, 0.3, 1.5, 0.1, -0.2, 0.1, 1.2;
  const Eigen::Vector3d rStick(1.0, -0.2, 0.1);
  return {
      {"separating", spd, Eigen::Vector3d(1.0, 0.5, -0.2), 0.5, Eigen::Vector3d::Zero()},
      {"sticking", spd, -spd * rStick, 0.5, rStick},
      // W = diag(2, 1, 1): r_N = 1, r_T = -mu r_N q_T/|q_T|, u_T = (2.7, 3.6) along q_T.
      {"sliding", Eigen::Vector3d(2, 1, 1).asDiagonal(), Eigen::Vector3d(-2, 3, 4), 0.5,
       Eigen::Vector3d(1, -0.3, -0.4)},
      {"frictionless", spd, Eigen::Vector3d(-2, 1, 1), 0.0, Eigen::Vector3d::Zero()},
  };
}

}  // namespace

TEST(ContactSolver, AnalyticSingleContactForEverySolver) {
  const SolverRegistry registry = SolverRegistry::builtIn();
  SolverOptions o;
  o.tolerance = 1e-14;
  for (Analytic c : analyticCases()) {
    if (c.mu == 0.0) c.r = Eigen::Vector3d(2.0 / c.W(0, 0), 0, 0);  // u_N = 0, r_T = 0
    for (const SolverEntry& e : registry.entries()) {
      if (e.name == "ldlt") continue;   // equality rows only: EqualityLdltSolverTest
      if (e.name == "lemke") continue;  // faceted cone by design: LemkeSolverTest
      const SolveOutcome out = e.create()->solve(fixtures::singleContact(c.W, c.q, c.mu), o);
      EXPECT_LT((out.impulses - c.r).norm(), 1e-12) << e.name << " " << c.name;
      EXPECT_LT(out.report.residual, 1e-12) << e.name << " " << c.name;
      EXPECT_EQ(out.report.solver, e.name);
      EXPECT_GE(out.report.seconds, 0.0);
    }
  }
}

TEST(ContactSolver, InvalidProblemsAreReportedNotSolved) {
  const SolverRegistry registry = SolverRegistry::builtIn();
  ContactProblem nanW =
      fixtures::singleContact(Eigen::Matrix3d::Identity(), Eigen::Vector3d(-1, 0, 0), 0.3);
  Eigen::Matrix3d W = Eigen::Matrix3d::Identity();
  W(1, 2) = std::numeric_limits<double>::quiet_NaN();
  nanW.W = DelassusOperator::dense(W);
  ContactProblem negativeMu =
      fixtures::singleContact(Eigen::Matrix3d::Identity(), Eigen::Vector3d(-1, 0, 0), -0.3);
  ContactProblem wrongSize =
      fixtures::singleContact(Eigen::Matrix3d::Identity(), Eigen::Vector3d(-1, 0, 0), 0.3);
  wrongSize.q = Eigen::VectorXd::Ones(4);
  for (const SolverEntry& e : registry.entries()) {
    for (const ContactProblem* p : {&nanW, &negativeMu, &wrongSize}) {
      const SolveOutcome out = e.create()->solve(*p);
      EXPECT_EQ(out.report.status, SolverStatus::InvalidProblem) << e.name;
      EXPECT_FALSE(out.report.message.empty());
      EXPECT_TRUE(out.impulses.allFinite());
    }
    SolverOptions bad;
    bad.tolerance = -1;
    EXPECT_EQ(e.create()
                  ->solve(fixtures::singleContact(Eigen::Matrix3d::Identity(),
                                                  Eigen::Vector3d(-1, 0, 0), 0.3),
                          bad)
                  .report.status,
              SolverStatus::InvalidProblem);
  }
}

TEST(ContactSolver, EmptyAndSeparatingProblemsReturnAtOnce) {
  const SolverRegistry registry = SolverRegistry::builtIn();
  for (const SolverEntry& e : registry.entries()) {
    if (e.name == "ldlt") continue;  // equality rows only: EqualityLdltSolverTest
    const SolveOutcome empty = e.create()->solve(ContactProblem{});
    EXPECT_EQ(empty.report.status, SolverStatus::Converged);
    EXPECT_EQ(empty.report.iterations, 0);
    EXPECT_EQ(empty.impulses.size(), 0);
    const SolveOutcome apart = e.create()->solve(
        fixtures::singleContact(Eigen::Matrix3d::Identity(), Eigen::Vector3d(0.1, 5, 5), 0.3));
    EXPECT_EQ(apart.report.status, SolverStatus::Converged);
    EXPECT_EQ(apart.report.iterations, 0);
  }
}

TEST(ContactSolver, WarmStartAtTheSolutionCostsNothing) {
  ContactProblem p = fixtures::randomMechanical(4, 20, 0.4, 5);
  const SolverRegistry registry = SolverRegistry::builtIn();
  for (const SolverEntry& e : registry.entries()) {
    if (e.name == "ldlt") continue;   // equality rows only: EqualityLdltSolverTest
    if (e.name == "lemke") continue;  // faceted cone by design: LemkeSolverTest
    const SolveOutcome cold = e.create()->solve(p);
    ASSERT_TRUE(cold.report.converged()) << e.name << " " << cold.report.message;
    ContactProblem warm = p;
    warm.warmStart = cold.impulses;
    const SolveOutcome again = e.create()->solve(warm);
    EXPECT_EQ(again.report.iterations, 0) << e.name;
    // A useless warm start (far outside) is dropped for r = 0 and noted.
    warm.warmStart = Eigen::VectorXd::Constant(p.size(), 1e6);
    const SolveOutcome bad = e.create()->solve(warm);
    EXPECT_TRUE(bad.report.converged());
    EXPECT_NE(bad.report.message.find("warm start ignored"), std::string::npos) << e.name;
  }
}

TEST(ContactSolver, AnisotropicSlipDirection) {
  // W = I, q = (-1, 3, 3), mu1 = 0.2, mu2 = 0.6: maximal dissipation on the ellipse gives
  // r_T = -r_N M^2 u_T / ||M u_T|| with u = r + q, u_N = 0 -> r_N = 1; solve the 2D fixed point
  // by checking the residual only (the direction is not along q_T).
  ContactProblem p;
  p.blocks = {ConstraintBlock::anisotropicContact(0.2, 0.6)};
  p.W = DelassusOperator::dense(Eigen::Matrix3d::Identity());
  p.q = Eigen::Vector3d(-1, 3, 3);
  SolverOptions o;
  o.tolerance = 1e-12;
  const SolverRegistry registry = SolverRegistry::builtIn();
  for (const SolverEntry& e : registry.entries()) {
    if (e.name == "ldlt") continue;   // equality rows only: EqualityLdltSolverTest
    if (e.name == "lemke") continue;  // faceted cone by design: LemkeSolverTest
    const SolveOutcome out = e.create()->solve(p, o);
    EXPECT_LT(out.report.residual, 1e-11) << e.name;
    const Eigen::Vector3d r = out.impulses, u = r + p.q;
    EXPECT_NEAR(std::hypot(r[1] / 0.2, r[2] / 0.6), r[0], 1e-10);  // on the ellipse
    EXPECT_NEAR(u[0], 0.0, 1e-10);
    const Eigen::Vector2d expected =
        -r[0] * Eigen::Vector2d(0.04 * u[1], 0.36 * u[2]) / std::hypot(0.2 * u[1], 0.6 * u[2]);
    EXPECT_LT((r.tail<2>() - expected).norm(), 1e-10) << e.name;
  }
}

namespace {

// Returns a huge answer inside the cone (a pivoting solver on a bad basis does that).
class WildSolver final : public ContactSolver {
 public:
  [[nodiscard]] std::string name() const override { return "wild"; }
  void solvePrepared(const PreparedProblem& /*problem*/, const SolveContext& /*context*/,
                     Eigen::VectorXd& r, SolverReport& report) const override {
    r.setZero();
    r[0] = 1e6;
    report.status = SolverStatus::Stalled;
  }
};

}  // namespace

// With neverWorseThanStart (the World's option), an answer above the tolerance and worse than the
// start is never returned (issue 24 item 4): the start (here the warm start, projected onto the
// cone) comes back, with the solver's status. Off (the default), the solver's own answer is.
TEST(ContactSolver, AnAnswerWorseThanItsStartIsNotReturnedWhenAsked) {
  const Eigen::Matrix3d W = Eigen::Vector3d(2, 1, 1).asDiagonal();
  ContactProblem p = fixtures::singleContact(W, Eigen::Vector3d(-2, 0.1, 0), 0.5);
  EXPECT_EQ(WildSolver().solve(p).impulses[0], 1e6);
  SolverOptions safe;
  safe.neverWorseThanStart = true;
  SolveOutcome out = WildSolver().solve(p, safe);
  EXPECT_EQ(out.report.status, SolverStatus::Stalled);
  EXPECT_EQ(out.impulses, Eigen::Vector3d::Zero()) << "r = 0 is the start without a warm start";
  EXPECT_NE(out.report.message.find("the start is returned"), std::string::npos)
      << out.report.message;
  EXPECT_DOUBLE_EQ(out.report.residual, commonResidual(p, out.impulses).relative);
  p.warmStart = Eigen::Vector3d(0.9, 0.0, 1.0);  // outside the cone: projected first
  out = WildSolver().solve(p, safe);
  EXPECT_LT((out.impulses - Eigen::Vector3d(0.9, 0.0, 1.0)).norm(), 1.0);
  EXPECT_LE(std::hypot(out.impulses[1], out.impulses[2]), 0.5 * out.impulses[0] + 1e-12);
  EXPECT_LT(out.report.residual, 1.0);
}

// The report's residual is the common residual of the returned impulses, bit for bit, and the
// returned velocities are W r + q, whether ContactSolver computes it after the solve or reads it
// from the solver's last evaluation (Newton's answer, an accepted warm start: PreparedProblem::
// end), on block-sparse W (the World's small islands) as on the fixtures' own storage.
TEST(ContactSolver, TheReportedResidualIsTheCommonResidualOfTheAnswer) {
  const SolverRegistry registry = SolverRegistry::builtIn();
  for (const char* name : fixtures::kFixtures) {
    ContactProblem original = fixtures::loadFixture(name);
    ContactProblem sparse = original;
    sparse.W = DelassusOperator::blockSparse(original.W.toBlockSparse(original.blockSizes()));
    for (ContactProblem* p : {&original, &sparse}) {
      for (const char* solver : {"ac_newton", "fb_newton", "bgs", "pgs"}) {
        SolverOptions o;
        o.tolerance = 1e-8;
        o.maxIterations = 300;
        const std::unique_ptr<ContactSolver> s = registry.create(solver);
        const SolveOutcome cold = s->solve(*p, o);
        // Warm-started at its own answer: the start is the answer (no iteration when converged).
        ContactProblem warm = *p;
        warm.warmStart = cold.impulses;
        const SolveOutcome again = s->solve(warm, o);
        for (const SolveOutcome* out : {&cold, &again}) {
          Eigen::VectorXd u;
          const ResidualValue expected = commonResidual(*p, out->impulses, u);
          EXPECT_EQ(out->report.residual, expected.relative) << name << " " << solver;
          EXPECT_EQ(out->report.absoluteResidual, expected.absolute) << name << " " << solver;
          EXPECT_EQ(out->velocities, u) << name << " " << solver;
        }
      }
    }
  }
}
