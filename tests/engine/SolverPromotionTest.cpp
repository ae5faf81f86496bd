// engine/SolverPromotion: the promotion rule of the solve policy (solvers::PromotionRule): which
// plan an island gets after a fallback finished its last step, and when a promotion is recorded
// or cleared.
#include <coulomb/engine/SolverPromotion.hpp>

#include <gtest/gtest.h>

using namespace coulomb;

namespace {

// The default thresholds, switched on (the rule is off by default).
const solvers::PromotionRule kRule = [] {
  solvers::PromotionRule rule;
  rule.enabled = true;
  return rule;
}();

solvers::SolvePlan pilePlan() {
  solvers::SolvePlan plan;
  plan.attempts = {{"pgs", 0, 20}, {"ac_newton"}, {"bgs"}};
  plan.options.tolerance = 1e-6;
  plan.rule = solvers::PlanRule::PileByNu;
  plan.features.unknowns = kRule.minUnknowns + 1;
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

std::vector<std::string> names(const solvers::SolvePlan& plan) {
  std::vector<std::string> out;
  for (const solvers::SolveAttempt& a : plan.attempts) out.push_back(a.solver);
  return out;
}

}  // namespace

TEST(SolverPromotionTest, NothingRecordedLeavesThePlan) {
  engine::SolverPromotion promotion;
  promotion.resize(4);
  solvers::SolvePlan plan = pilePlan();
  promotion.apply(islandOf({1, 2}), kRule, plan);
  EXPECT_FALSE(plan.promoted);
  EXPECT_EQ(plan.attempts, pilePlan().attempts);
}

TEST(SolverPromotionTest, FallbackGoesFirstOnceWithItsOwnSettings) {
  engine::SolverPromotion promotion;
  promotion.resize(4);
  const engine::Island island = islandOf({1, 2});
  promotion.record(island, kRule, true, pilePlan(), fellBackTo("ac_newton"));
  EXPECT_EQ(promotion.names()[1], "ac_newton");
  EXPECT_EQ(promotion.names()[0], "");  // not in the island

  solvers::SolvePlan plan = pilePlan();
  promotion.apply(island, kRule, plan);
  ASSERT_TRUE(plan.promoted);
  // The promoted attempt (capped, tighter) goes first; the plan follows unchanged, so a failed
  // promotion still gets pgs and the full ac_newton fallback.
  EXPECT_EQ(names(plan), (std::vector<std::string>{"ac_newton", "pgs", "ac_newton", "bgs"}));
  EXPECT_EQ(plan.attempts[0].maxIterations, kRule.iterationCap);
  EXPECT_EQ(plan.attempts[0].stallWindow, 0);
  EXPECT_DOUBLE_EQ(plan.attempts[0].tolerance, kRule.toleranceScale * 1e-6);
  EXPECT_EQ(plan.attempts[1], pilePlan().attempts[0]);
  EXPECT_NE(plan.reason().find("ac_newton first"), std::string::npos);

  // The promoted step never promotes again, even when it fell back itself.
  promotion.record(island, kRule, true, plan, fellBackTo("bgs"));
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
  promotion.record(island, kRule, true, pilePlan(), converged);
  EXPECT_EQ(promotion.names()[0], "");

  solvers::PlanOutcome failed = fellBackTo("ac_newton");  // the fallback did not converge either
  failed.attempts.back().status = solvers::SolverStatus::MaxIterations;
  failed.best.report = failed.attempts.back();
  promotion.record(island, kRule, true, pilePlan(), failed);
  EXPECT_EQ(promotion.names()[0], "");

  solvers::PlanOutcome farOff = fellBackTo("ac_newton");  // pgs far above the tolerance:
  farOff.attempts.front().residual = 1e-2;                // Newton did real work, no alternation
  promotion.record(island, kRule, true, pilePlan(), farOff);
  EXPECT_EQ(promotion.names()[0], "");
  solvers::PlanOutcome slow = fellBackTo("ac_newton");  // a long fallback: no quick finish
  slow.attempts.back().iterations = kRule.iterationCap + 1;
  slow.best.report = slow.attempts.back();
  promotion.record(island, kRule, true, pilePlan(), slow);
  EXPECT_EQ(promotion.names()[0], "");
  promotion.record(island, kRule, true, pilePlan(), fellBackTo("ac_newton"));
  EXPECT_EQ(promotion.names()[0], "ac_newton");
}

TEST(SolverPromotionTest, APromotedSolverOutsideThePlanIsIgnored) {
  engine::SolverPromotion promotion;
  promotion.resize(2);
  const engine::Island island = islandOf({0, 1});
  promotion.record(island, kRule, true, pilePlan(), fellBackTo("fb_newton"));
  solvers::SolvePlan plan = pilePlan();
  promotion.apply(island, kRule, plan);
  EXPECT_FALSE(plan.promoted);
  EXPECT_EQ(plan.attempts.front().solver, "pgs");
}

// The rule is data of the policy: off, for small islands or for a named choice nothing is
// promoted, and its thresholds are the ones the policy holds.
TEST(SolverPromotionTest, TheRuleIsThePolicys) {
  engine::SolverPromotion promotion;
  promotion.resize(1);
  const engine::Island island = islandOf({0});
  solvers::PromotionRule off = kRule;
  off.enabled = false;
  promotion.record(island, off, true, pilePlan(), fellBackTo("ac_newton"));
  EXPECT_EQ(promotion.names()[0], "");
  promotion.record(island, kRule, false, pilePlan(), fellBackTo("ac_newton"));  // named choice
  EXPECT_EQ(promotion.names()[0], "");
  solvers::SolvePlan small = pilePlan();
  small.features.unknowns = kRule.minUnknowns;
  promotion.record(island, kRule, true, small, fellBackTo("ac_newton"));
  EXPECT_EQ(promotion.names()[0], "");

  solvers::PromotionRule tight = kRule;
  tight.nearMiss = 1.2;  // pgs ended at 1.5x the tolerance: no longer a near miss
  promotion.record(island, tight, true, pilePlan(), fellBackTo("ac_newton"));
  EXPECT_EQ(promotion.names()[0], "");
  solvers::PromotionRule everywhere = kRule;
  everywhere.minUnknowns = 0;
  everywhere.iterationCap = 2;
  everywhere.toleranceScale = 0.5;
  promotion.record(island, everywhere, true, small, fellBackTo("ac_newton"));
  EXPECT_EQ(promotion.names()[0], "ac_newton");
  solvers::SolvePlan plan = small;
  promotion.apply(island, everywhere, plan);
  ASSERT_TRUE(plan.promoted);
  EXPECT_EQ(plan.attempts[0].maxIterations, 2);
  EXPECT_DOUBLE_EQ(plan.attempts[0].tolerance, 0.5e-6);
}
