#include <gtest/gtest.h>
#include <coulomb/solvers/GaussSeidelLoop.hpp>
#include <coulomb/solvers/bgs/BgsSolver.hpp>
#include <coulomb/solvers/pgs/PgsSolver.hpp>

#include <thread>
#include <vector>

#include "TestProblems.hpp"

using namespace coulomb::solvers;

namespace {
// A contact coupled to an equality row, a bounded row and a unilateral row.
ContactProblem mixedProblem() {
  ContactProblem p;
  p.blocks = {ConstraintBlock::contact(0.5), ConstraintBlock::equality(),
              ConstraintBlock::bounded(-0.2, 0.2), ConstraintBlock::unilateral()};
  Eigen::MatrixXd J(6, 6);
  J.setIdentity();
  J(3, 0) = 0.5;
  J(4, 1) = 0.3;
  J(5, 2) = -0.4;
  const Eigen::MatrixXd W = J * J.transpose();
  p.W = DelassusOperator::dense(W);
  p.q = (Eigen::VectorXd(6) << -1, 0.2, 0.1, 0.5, 1.0, -0.7).finished();
  return p;
}
}  // namespace

TEST(GaussSeidelLoop, SolvesScalarRowsExactly) {
  const ContactProblem p = mixedProblem();
  ASSERT_FALSE(p.validate().has_value());
  const PreparedProblem pp = PreparedProblem::from(p);
  SolverOptions o;
  o.tolerance = 1e-13;
  const SolveContext context(o, SolveContext::Clock::now());
  Eigen::VectorXd r = Eigen::VectorXd::Zero(6);
  SolverReport report;
  auto keepRule = [](int, const Eigen::Vector3d&, Eigen::Vector3d&) {};
  const ContactUpdate keep(keepRule);
  // With the contact frozen at 0, the scalar rows alone must reach their exact values.
  runGaussSeidel(pp, context, GaussSeidelSettings{}, keep, r, report);
  Eigen::VectorXd u;
  pp.velocity(r, u);
  EXPECT_NEAR(u[3], 0.0, 1e-12);                             // equality: u = 0
  EXPECT_TRUE(r[4] >= -0.2 - 1e-15 && r[4] <= 0.2 + 1e-15);  // bounded
  EXPECT_GE(r[5], 0.0);                                      // unilateral
  EXPECT_GT(report.iterations, 0);
}

TEST(GaussSeidelLoop, PgsOnMixedRowsAndDeterministicShuffle) {
  const ContactProblem p = mixedProblem();
  SolverOptions o;
  o.tolerance = 1e-12;
  PgsOptions shuffled;
  shuffled.shuffle = true;
  shuffled.seed = 42;
  const SolveOutcome a = PgsSolver(shuffled).solve(p, o), b = PgsSolver(shuffled).solve(p, o);
  EXPECT_EQ(a.report.status, SolverStatus::Converged) << a.report.message;
  EXPECT_LE(a.report.residual, 1e-12);
  EXPECT_EQ(a.impulses, b.impulses);  // same seed, same bits
  EXPECT_EQ(a.report.iterations, b.report.iterations);
}

TEST(GaussSeidelLoop, StallIsReportedAndTimeLimitHonoured) {
  const ContactProblem p = fixtures::randomMechanical(6, 10, 0.5, 9);  // nu = 1.8
  const PreparedProblem pp = PreparedProblem::from(p);
  SolverOptions o;
  o.tolerance = 0;  // unreachable
  o.maxIterations = 100000;
  const SolveContext context(o, SolveContext::Clock::now());
  Eigen::VectorXd r = Eigen::VectorXd::Zero(pp.size());
  SolverReport report;
  GaussSeidelSettings s;
  s.stallWindow = 50;
  auto nothing = [](int, const Eigen::Vector3d&, Eigen::Vector3d&) {};
  runGaussSeidel(pp, context, s, ContactUpdate(nothing), r, report);
  EXPECT_EQ(report.status, SolverStatus::Stalled);
  o.timeLimitSeconds = 0.01;
  SolverReport timed;
  PgsOptions noStall;
  noStall.stallWindow = 1 << 30;
  const SolveOutcome out = PgsSolver(noStall).solve(p, o);
  EXPECT_TRUE(out.report.timeLimitReached);
  EXPECT_EQ(out.report.status, SolverStatus::MaxIterations);
  EXPECT_LT(out.report.seconds, 1.0);
}

TEST(GaussSeidelLoop, OptionsStallWindowShortensTheSolversOwn) {
  // The frozen update never lowers the residual: the stall test fires at the first check after
  // the window (SolverOptions::stallWindow = 20 < the settings' 500), not at the 500-sweep one.
  const ContactProblem p = fixtures::randomMechanical(6, 10, 0.5, 9);
  const PreparedProblem pp = PreparedProblem::from(p);
  auto frozenRule = [](int, const Eigen::Vector3d&, Eigen::Vector3d&) {};
  const ContactUpdate frozen(frozenRule);
  auto sweepsUntilStall = [&](int optionsWindow) {
    SolverOptions o;
    o.tolerance = 0;  // unreachable
    o.maxIterations = 100000;
    o.stallWindow = optionsWindow;
    const SolveContext context(o, SolveContext::Clock::now());
    Eigen::VectorXd r = Eigen::VectorXd::Zero(pp.size());
    SolverReport report;
    GaussSeidelSettings s;
    s.stallWindow = 500;
    runGaussSeidel(pp, context, s, frozen, r, report);
    EXPECT_EQ(report.status, SolverStatus::Stalled);
    return report.iterations;
  };
  EXPECT_LE(sweepsUntilStall(20), 25);
  EXPECT_GE(sweepsUntilStall(0), 500);     // 0: the solver's own window
  EXPECT_GE(sweepsUntilStall(1000), 500);  // never longer than the solver's own
}

namespace {
// Runs the tasks on three std::threads, each taking every third index from the top down: an
// order no serial loop has, and true concurrency for the sanitizers.
class ThreeThreads final : public ParallelLoop {
 public:
  void forEach(std::size_t count, IndexTask task) override {
    ++calls;
    std::vector<std::thread> threads;
    for (std::size_t t = 0; t < 3; ++t)
      threads.emplace_back([&, t] {
        for (std::size_t i = count; i-- > 0;)
          if (i % 3 == t) task(i);
      });
    for (std::thread& thread : threads) thread.join();
  }
  [[nodiscard]] int threads() const override { return 3; }
  int calls = 0;
};

SolveOutcome solveGrid(const ContactProblem& p, const ContactSolver& solver, int partBlocks,
                       ParallelLoop* parallel) {
  SolverOptions o;
  o.tolerance = 1e-10;
  o.maxIterations = 60;
  o.sweepPartBlocks = partBlocks;
  o.parallel = parallel;
  return solver.solve(p, o);
}
}  // namespace

TEST(GaussSeidelLoop, ASplitSweepOnThreadsGivesTheBitsOfTheSerialOne) {
  // 24 x 24 bodies, 2 points per touching pair: 2 256 blocks in 8 parts, and the boundary's
  // colours of a few hundred blocks each (split over threads too).
  const ContactProblem p = fixtures::bodyGrid(24, 2, 0.5, 11);
  PgsOptions shuffled;
  shuffled.shuffle = true;  // permutes within each part and each colour
  shuffled.seed = 5;
  for (const PgsOptions& options : {PgsOptions{}, shuffled}) {
    const PgsSolver pgs(options);
    ThreeThreads threads;
    const SolveOutcome serial = solveGrid(p, pgs, 282, nullptr);
    const SolveOutcome parallel = solveGrid(p, pgs, 282, &threads);
    EXPECT_GT(threads.calls, 0);  // the sweep did run on the threads
    EXPECT_EQ(serial.impulses, parallel.impulses);
    EXPECT_EQ(serial.report.iterations, parallel.report.iterations);
    EXPECT_EQ(serial.report.residual, parallel.report.residual);
    // The split order is another order than the block order (other iterates), converging
    // as fast: 60 sweeps take the residual from O(1) to below 1e-2 in both.
    const SolveOutcome blockOrder = solveGrid(p, pgs, 0, nullptr);
    EXPECT_NE(blockOrder.impulses, serial.impulses);
    EXPECT_LT(serial.report.residual, 1e-2);
    EXPECT_LT(blockOrder.report.residual, 1e-2);
    EXPECT_LT(serial.report.residual, 2 * blockOrder.report.residual);
  }
}

TEST(GaussSeidelLoop, BelowTwoPartsTheThreadsAreNotUsed) {
  const ContactProblem p = fixtures::bodyGrid(4, 2, 0.5, 2);
  const int blocks = static_cast<int>(p.blocks.size());
  ThreeThreads threads;
  const SolveOutcome lent = solveGrid(p, BgsSolver(), blocks / 2 + 1, &threads);
  EXPECT_EQ(threads.calls, 0);
  EXPECT_EQ(lent.impulses, solveGrid(p, BgsSolver(), 0, nullptr).impulses);  // block order
}
