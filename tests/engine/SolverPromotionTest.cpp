// engine/SolverPromotion: which plan an island gets after a fallback finished its last step, and
// when a promotion is recorded or cleared.
#include <coulomb/engine/SolverPromotion.hpp>

#include <gtest/gtest.h>

using namespace coulomb;

namespace {

solvers::SolvePlan pilePlan() {
  solvers::SolvePlan plan;
  plan.solvers = {"pgs", "ac_newton", "bgs"};
  plan.stallWindows = {20};
  plan.options.tolerance = 1e-6;
  plan.reason = "pile";
  return plan;
}

solvers::SolverReport attempt(const std::string& solver, solvers::SolverStatus status) {
  solvers::SolverReport r;
  r.solver = solver;
  r.status = status;
  return r;
}

solvers::PlanOutcome fellBackTo(const std::string& solver) {
  solvers::PlanOutcome outcome;
  outcome.attempts = {attempt("pgs", solvers::SolverStatus::Stalled),
                      attempt(solver, solvers::SolverStatus::Converged)};
  outcome.attempts.front().residual = 1.5e-6;  // just above pilePlan's 1e-6
  outcome.attempts.back().residual = 1e-9;
  outcome.attempts.back().iterations = 1;
  outcome.best.report = outcome.attempts.back();
  return outcome;
}

engine::Island islandOf(std::vector<std::int32_t> bodies) {
  engine::Island island;
  island.bodies = std::move(bodies);
  return island;
}

}  // namespace

TEST(SolverPromotionTest, NothingRecordedLeavesThePlan) {
  engine::SolverPromotion promotion;
  promotion.resize(4);
  bool promoted = true;
  const solvers::SolvePlan plan = promotion.apply(islandOf({1, 2}), pilePlan(), promoted);
  EXPECT_FALSE(promoted);
  EXPECT_EQ(plan.solvers, pilePlan().solvers);
  EXPECT_EQ(plan.stallWindows, pilePlan().stallWindows);
}

TEST(SolverPromotionTest, FallbackGoesFirstOnceWithItsOwnSettings) {
  engine::SolverPromotion promotion;
  promotion.resize(4);
  const engine::Island island = islandOf({1, 2});
  promotion.record(island, pilePlan(), fellBackTo("ac_newton"), false);
  EXPECT_EQ(promotion.names()[1], "ac_newton");
  EXPECT_EQ(promotion.names()[0], "");  // not in the island

  bool promoted = false;
  const solvers::SolvePlan plan = promotion.apply(island, pilePlan(), promoted);
  ASSERT_TRUE(promoted);
  // The promoted attempt (capped, tighter) goes first; the plan follows unchanged, so a failed
  // promotion still gets pgs and the full ac_newton fallback.
  EXPECT_EQ(plan.solvers, (std::vector<std::string>{"ac_newton", "pgs", "ac_newton", "bgs"}));
  EXPECT_EQ(plan.stallWindows, (std::vector<int>{0, 20, 0, 0}));
  EXPECT_EQ(plan.iterationCaps, (std::vector<int>{engine::kPromotedIterationCap, 0, 0, 0}));
  ASSERT_EQ(plan.tolerances.size(), 4u);
  EXPECT_DOUBLE_EQ(plan.tolerances.front(), engine::kPromotedToleranceScale * 1e-6);
  EXPECT_EQ(plan.tolerances[1], 0.0);
  EXPECT_NE(plan.reason.find("ac_newton first"), std::string::npos);

  // The promoted step never promotes again, even when it fell back itself.
  promotion.record(island, plan, fellBackTo("bgs"), true);
  EXPECT_EQ(promotion.names()[1], "");
  EXPECT_EQ(promotion.names()[2], "");
}

TEST(SolverPromotionTest, OnlyAFallbackThatConvergedAfterAFailedPrimaryIsPromoted) {
  engine::SolverPromotion promotion;
  promotion.resize(3);
  const engine::Island island = islandOf({0});
  solvers::PlanOutcome converged;  // the primary converged: nothing to promote
  converged.attempts = {attempt("pgs", solvers::SolverStatus::Converged)};
  converged.best.report = converged.attempts.front();
  promotion.record(island, pilePlan(), converged, false);
  EXPECT_EQ(promotion.names()[0], "");

  solvers::PlanOutcome failed = fellBackTo("ac_newton");  // the fallback did not converge either
  failed.attempts.back().status = solvers::SolverStatus::MaxIterations;
  failed.best.report = failed.attempts.back();
  promotion.record(island, pilePlan(), failed, false);
  EXPECT_EQ(promotion.names()[0], "");

  solvers::PlanOutcome farOff = fellBackTo("ac_newton");  // pgs far above the tolerance:
  farOff.attempts.front().residual = 1e-2;                // Newton did real work, no alternation
  promotion.record(island, pilePlan(), farOff, false);
  EXPECT_EQ(promotion.names()[0], "");
  solvers::PlanOutcome slow = fellBackTo("ac_newton");  // a long fallback: no quick finish
  slow.attempts.back().iterations = engine::kPromotedIterationCap + 1;
  slow.best.report = slow.attempts.back();
  promotion.record(island, pilePlan(), slow, false);
  EXPECT_EQ(promotion.names()[0], "");
  promotion.record(island, pilePlan(), fellBackTo("ac_newton"), false);
  EXPECT_EQ(promotion.names()[0], "ac_newton");
}

TEST(SolverPromotionTest, APromotedSolverOutsideThePlanIsIgnored) {
  engine::SolverPromotion promotion;
  promotion.resize(2);
  const engine::Island island = islandOf({0, 1});
  promotion.record(island, pilePlan(), fellBackTo("fb_newton"), false);
  solvers::SolvePlan plan = pilePlan();
  bool promoted = true;
  plan = promotion.apply(island, plan, promoted);
  EXPECT_FALSE(promoted);
  EXPECT_EQ(plan.solvers.front(), "pgs");
}
