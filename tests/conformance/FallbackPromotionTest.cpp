// Fallback promotion (engine/SolverPromotion; docs/benchmarks.md, "Long runs"). From step 330 of
// pyramid_10 (tests/data/snapshots) plain Gauss-Seidel stagnated just above the tolerance and
// ac_newton finished the step; the impulses of that step carried a one-off correction, so with the
// warm start the next steps alternated Gauss-Seidel -> ac_newton. The cause was the stagnation:
// the pile plan's nncg (Gauss-Seidel with conjugate-gradient momentum) converges there, and the
// alternation is gone without promotion. Promotion stays a rule of the policy for the rare
// fallback that remains.
#include <gtest/gtest.h>
#include <coulomb/engine/World.hpp>
#include <coulomb/io/Snapshot.hpp>

#include "scenes/SceneRegistry.hpp"

#include <cstdint>
#include <string>
#include <vector>

using namespace coulomb;

namespace {

void setPromotion(engine::World& world, bool on, int iterationCap = 0) {
  solvers::SolvePolicy policy = world.settings().solve;
  policy.promotion.enabled = on;
  if (iterationCap > 0) policy.options.maxIterations = iterationCap;
  world.setSolvePolicy(policy);
}

struct LongRunCounts {
  int steps = 0, fallbacks = 0, newtonSolves = 0, promoted = 0, unconverged = 0;
  double maxResidual = 0.0;
};

LongRunCounts continuePyramid(bool promote, int steps) {
  const engine::io::Scene scene = scenes::loadBuiltinScene("pyramid_10");
  engine::World world = engine::io::buildWorld(scene);
  engine::io::loadSnapshotFile(
      world, std::string(COULOMB_TEST_DATA_DIR) + "/snapshots/pyramid_10_step330.snap");
  setPromotion(world, promote);
  LongRunCounts counts;
  for (int k = 0; k < steps; ++k) {
    const engine::StepReport report = world.step(scene.settings.timeStep);
    ++counts.steps;
    counts.fallbacks += static_cast<int>(report.fallbacks());
    for (const engine::IslandReport& island : report.islands) {
      for (const solvers::SolverReport& attempt : island.attempts)
        counts.newtonSolves += attempt.solver == "ac_newton" ? 1 : 0;
      if (island.plan.promoted) ++counts.promoted;
      if (!island.converged()) ++counts.unconverged;
      counts.maxResidual = std::max(counts.maxResidual, island.solve.residual);
    }
  }
  return counts;
}

#ifdef COULOMB_SANITIZE
constexpr int kSteps = 60;  // ASan/UBSan: the first alternations and the promotion are in here
#else
constexpr int kSteps = 200;
#endif

}  // namespace

TEST(FallbackPromotion, WithPromotionThePilePlanStillConverges) {
  // The rule itself is tested in tests/engine/SolverPromotionTest.cpp; here: on (as users may
  // set it) it changes nothing where nothing falls back.
  const LongRunCounts c = continuePyramid(true, kSteps);
  std::printf(
      "promotion: %d steps, %d fallbacks, %d ac_newton solves, %d promoted, residual max %.3g\n",
      c.steps, c.fallbacks, c.newtonSolves, c.promoted, c.maxResidual);
  EXPECT_EQ(c.unconverged, 0);
  EXPECT_LE(c.maxResidual, 1e-6);
  EXPECT_LE(c.fallbacks, 4);
  EXPECT_LE(c.newtonSolves, 8);
}

TEST(FallbackPromotion, WithoutPromotionNoAlternation) {
  // WorldSettings::solve.promotion off: the pile plan's first solver converges on its own (with
  // plain pgs first, 50 or more of these 200 steps fell back to ac_newton, every other step).
  const LongRunCounts c = continuePyramid(false, kSteps);
  std::printf("no promotion: %d steps, %d fallbacks, %d ac_newton solves, residual max %.3g\n",
              c.steps, c.fallbacks, c.newtonSolves, c.maxResidual);
  EXPECT_EQ(c.promoted, 0);
  EXPECT_EQ(c.unconverged, 0);
  EXPECT_LE(c.maxResidual, 1e-6);
  EXPECT_LE(c.fallbacks, 4);
}

TEST(FallbackPromotion, APendingPromotionIsPartOfTheSnapshot) {
  // Save right after a fallback (a promotion pending), restore into a fresh World, and both go on
  // bit for bit; the restored one runs the promoted solver first. A cap of one sweep per attempt
  // makes the pile plan's first solver miss the tolerance narrowly, so Newton finishes steps.
  const engine::io::Scene scene = scenes::loadBuiltinScene("pyramid_10");
  engine::World world = engine::io::buildWorld(scene);
  engine::io::loadSnapshotFile(
      world, std::string(COULOMB_TEST_DATA_DIR) + "/snapshots/pyramid_10_step330.snap");
  setPromotion(world, true, 1);
  bool pending = false;
  for (int k = 0; k < 40 && !pending; ++k) {
    const engine::StepReport report = world.step(scene.settings.timeStep);
    pending = report.fallbacks() > 0;
  }
  ASSERT_TRUE(pending) << "no fallback within 40 steps of step 330";
  const std::vector<std::uint8_t> bytes = engine::io::saveSnapshot(world);
  engine::World restored = engine::io::buildWorld(scene);
  engine::io::restoreSnapshot(restored, bytes, "memory");
  for (int k = 0; k < 20; ++k) {
    const engine::StepReport a = world.step(scene.settings.timeStep);
    const engine::StepReport b = restored.step(scene.settings.timeStep);
    ASSERT_EQ(world.stateHash(), restored.stateHash()) << "step " << k;
    if (k == 0) {
      ASSERT_FALSE(b.islands.empty());
      EXPECT_TRUE(b.islands.front().plan.promoted) << b.islands.front().reason();
      EXPECT_EQ(a.islands.front().reason(), b.islands.front().reason());
    }
  }
}
