#include <gtest/gtest.h>
#include <coulomb/solvers/SolveWithFallback.hpp>
#include <coulomb/solvers/SolverChooser.hpp>
#include <coulomb/solvers/pgs/PgsSolver.hpp>

#include "TestProblems.hpp"

#include <memory>

using namespace coulomb::solvers;

namespace {

// Always reports a numerical failure (and leaves r as it found it).
class AlwaysFails final : public ContactSolver {
 public:
  [[nodiscard]] std::string name() const override { return "always_fails"; }
  void solvePrepared(const PreparedProblem&, const SolveContext&, Eigen::VectorXd&,
                     SolverReport& report) const override {
    report.status = SolverStatus::NumericalFailure;
    report.note("forced failure");
  }
};

// Records the start it was given (original variables), then does nothing.
class StartSpy final : public ContactSolver {
 public:
  explicit StartSpy(std::shared_ptr<Eigen::VectorXd> seen) : seen_(std::move(seen)) {}
  [[nodiscard]] std::string name() const override { return "spy"; }
  void solvePrepared(const PreparedProblem& p, const SolveContext&, Eigen::VectorXd& r,
                     SolverReport& report) const override {
    *seen_ = p.toOriginal(r);
    report.status = SolverStatus::Stalled;
  }

 private:
  std::shared_ptr<Eigen::VectorXd> seen_;
};

}  // namespace

TEST(SolveWithFallback, ForcedFailureFallsBackAndKeepsEveryReport) {
  SolverRegistry registry = SolverRegistry::builtIn();
  registry.add({"always_fails", "test", [] { return std::make_unique<AlwaysFails>(); }});
  const ContactProblem p = fixtures::randomMechanical(6, 30, 0.5, 5);
  SolvePlan plan = SolverChooser().choose(p, {30}, SolverChoice::preferred("always_fails"), {});
  ASSERT_EQ(plan.attempts.front().solver, "always_fails");
  const PlanOutcome out = solveWithFallback(p, plan, registry);
  ASSERT_GE(out.attempts.size(), 2u);
  EXPECT_EQ(out.attempts[0].status, SolverStatus::NumericalFailure);
  EXPECT_EQ(out.attempts[0].solver, "always_fails");
  EXPECT_EQ(out.fallbacks(), static_cast<int>(out.attempts.size()) - 1);
  EXPECT_TRUE(out.best.report.converged()) << out.best.report.message;
  EXPECT_TRUE(out.converged());
  EXPECT_TRUE(out.best.impulses.allFinite());
}

TEST(SolveWithFallback, FallbackStartsFromTheBestIterate) {
  SolverRegistry registry;
  registry.add({"pgs3", "3 sweeps", [] { return std::make_unique<PgsSolver>(); }});
  auto seen = std::make_shared<Eigen::VectorXd>();
  registry.add({"spy", "records", [seen] { return std::make_unique<StartSpy>(seen); }});
  const ContactProblem p = fixtures::randomMechanical(6, 30, 0.5, 6);
  SolvePlan plan;
  plan.attempts = {{"pgs3", 3}, {"spy"}};
  const PlanOutcome out = solveWithFallback(p, plan, registry);
  ASSERT_EQ(out.attempts.size(), 2u);
  EXPECT_EQ(out.attempts[0].iterations, 3);
  ASSERT_EQ(seen->size(), p.size());
  EXPECT_LT((*seen - out.best.impulses).norm(), 1e-12);  // the spy started where pgs stopped
}

TEST(SolveWithFallback, UnknownNamesAreReportedNotFatal) {
  const ContactProblem p = fixtures::randomMechanical(3, 30, 0.3, 1);
  SolvePlan plan;
  plan.attempts = {{"no_such_solver"}, {"bgs"}};
  const PlanOutcome out = solveWithFallback(p, plan, SolverRegistry::builtIn());
  ASSERT_EQ(out.attempts.size(), 2u);
  EXPECT_EQ(out.attempts[0].status, SolverStatus::NotApplicable);
  EXPECT_TRUE(out.best.report.converged());
  SolvePlan none;
  none.attempts = {{"no_such_solver"}};
  const PlanOutcome nothing = solveWithFallback(p, none, SolverRegistry::builtIn());
  EXPECT_EQ(nothing.best.impulses.size(), p.size());
  EXPECT_EQ(nothing.best.report.status, SolverStatus::NotApplicable);
}

TEST(SolveWithFallback, AutoIsDeterministic) {
  const ContactProblem p = fixtures::loadFixture("OneObject-i1028-138");
  const SolverRegistry registry = SolverRegistry::builtIn();
  const SolvePlan plan = SolverChooser().choose(p, {}, SolverChoice::automatic(), {});
  const PlanOutcome a = solveWithFallback(p, plan, registry);
  const PlanOutcome b = solveWithFallback(p, plan, registry);
  EXPECT_TRUE(a.best.report.converged());
  EXPECT_EQ(a.best.impulses, b.best.impulses);
  EXPECT_EQ(a.iterations(), b.iterations());
}

TEST(SolveWithFallback, PerAttemptToleranceIteratesAndCountsWithinThePlans) {
  // The attempt's own tolerance (1e-14) makes pgs iterate its 3 capped sweeps; it ends above that
  // but below the plan's tolerance: the attempt keeps its own status (max_iterations, never
  // rewritten), the plan is converged and no fallback runs.
  const ContactProblem p = fixtures::randomMechanical(6, 30, 0.5, 6);
  SolvePlan plan;
  plan.attempts = {{"pgs", 3, 0, 1e-14}, {"ac_newton"}};
  plan.options.tolerance = 0.5;
  const PlanOutcome out = solveWithFallback(p, plan, SolverRegistry::builtIn());
  ASSERT_EQ(out.attempts.size(), 1u);
  EXPECT_EQ(out.attempts[0].iterations, 3);
  EXPECT_GT(out.best.report.residual, 1e-14);
  EXPECT_LE(out.best.report.residual, 0.5);
  EXPECT_EQ(out.best.report.status, SolverStatus::MaxIterations);
  EXPECT_TRUE(out.converged());
  // Above the plan's tolerance it is not converged, and the fallback runs.
  plan.options.tolerance = 1e-13;
  const PlanOutcome strict = solveWithFallback(p, plan, SolverRegistry::builtIn());
  EXPECT_EQ(strict.attempts.size(), 2u);
  EXPECT_FALSE(strict.attempts[0].converged());
}

// Solvers are created once per SolverInstances and reused for every later solve.
TEST(SolveWithFallback, SolverInstancesAreCreatedOnce) {
  SolverRegistry registry = SolverRegistry::builtIn();
  auto created = std::make_shared<int>(0);
  registry.add({"counted", "counts its creations", [created] {
                  ++*created;
                  return std::make_unique<PgsSolver>();
                }});
  const ContactProblem p = fixtures::randomMechanical(4, 30, 0.5, 3);
  SolvePlan plan;
  plan.attempts = {{"counted"}};
  SolverInstances instances;
  for (int k = 0; k < 5; ++k) (void)solveWithFallback(p, plan, registry, instances);
  EXPECT_EQ(*created, 1);
  EXPECT_EQ(instances.get("counted", registry), instances.get("counted", registry));
  EXPECT_EQ(instances.get("nope", registry), nullptr);
}
