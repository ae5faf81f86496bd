// A resting tower keeps its warm start: an exact answer (the sticking start) leaves the load
// alone as the next warm start (SolveOutcome::nextWarmStart, docs/solvers.md "Sticking start"),
// so the next step meets it far within the tolerance. Before, the answer's one-off correction of
// the last step's leftover velocity error was kept too: from about step 1 000 box_stack_10
// alternated an exact step and a warm start accepted at the tolerance, every other step
// (388 exact steps after a miss in 1 500, each followed by a residual of 1e-6). The same for a
// Newton answer on an island with W's entries (SteadyWarmStartTest).
#include <gtest/gtest.h>
#include <coulomb/engine/World.hpp>
#include <coulomb/io/SceneLoader.hpp>

#include <vector>

#include "SimpleBodies.hpp"
#include "scenes/SceneRegistry.hpp"

using namespace coulomb;

TEST(RestingWarmStart, AnExactStepIsFollowedByAWarmStartWithinAHundredthOfTheTolerance) {
  engine::io::Scene scene = scenes::loadBuiltinScene("box_stack_10");
  engine::World world = engine::io::buildWorld(scene);
  const double tolerance = scene.settings.solve.options.tolerance;
  std::vector<double> residuals;
  for (int k = 0; k < 1500; ++k) {
    const engine::StepReport& report = world.step(scene.settings.timeStep);
    ASSERT_EQ(report.islands.size(), 1u) << "step " << k;
    residuals.push_back(report.islands.front().solve.residual);
  }
  int exactAfterMiss = 0;
  for (std::size_t k = 1; k + 1 < residuals.size(); ++k) {
    // An exact answer (the sticking start) after a step near the tolerance.
    if (!(residuals[k] < 2e-2 * tolerance && residuals[k - 1] > 0.1 * tolerance)) continue;
    ++exactAfterMiss;
    EXPECT_LT(residuals[k + 1], 1e-2 * tolerance) << "step " << k + 1;
  }
  EXPECT_LT(exactAfterMiss, 20);
  for (std::size_t k = 0; k < residuals.size(); ++k)
    EXPECT_LE(residuals[k], tolerance) << "step " << k;
}

// A heavy box resting on a light one (docs/scene-specifications.md A5, tolerance 1e-10, an island
// with W's entries solved by Newton): Newton's exact answer is followed by warm starts within the
// tolerance, not by another Newton iteration. Before the steady warm start (docs/solvers.md
// "Steady warm start") every other step took one (0.5 per step: the answer's one-off correction
// of the arrival errors, repeated by the next warm start, missed by those errors reversed).
TEST(RestingWarmStart, AHeavyBoxOnALightOneRestsWithoutNewtonIterations) {
  for (const char* name : {"mass_ratio_100kg_on_0_1kg", "mass_ratio_1000kg_on_1kg"}) {
    engine::io::Scene scene = scenes::loadBuiltinScene(name);
    engine::World world = engine::io::buildWorld(scene);
    const double tolerance = scene.settings.solve.options.tolerance;
    int iterations = 0;
    for (int k = 0; k < 1100; ++k) {
      const engine::StepReport& report = world.step(scene.settings.timeStep);
      ASSERT_EQ(report.islands.size(), 1u) << name << " step " << k;
      const engine::IslandReport& island = report.islands.front();
      EXPECT_LE(island.solve.residual, tolerance) << name << " step " << k;
      if (k >= 100) iterations += island.solve.iterations;
    }
    EXPECT_LT(iterations, 100) << name;  // 1 000 steps: about 500 before
  }
}

// A box lands on one that rests: the step its new contacts join the resting box's island, the
// island's problem keeps the resting contacts' warm start and starts the new contacts at zero.
// Before, one contact without a warm start dropped the whole island's (a settling packing or a
// landing column then solved cold on every step that a contact appeared).
TEST(RestingWarmStart, ANewContactKeepsTheIslandsWarmStart) {
  engine::World world;
  coulomb::testing::addFloor(world);
  coulomb::testing::addCube(world, {0, 0, 0.1});
  coulomb::testing::addCube(world, {0.02, 0.01, 0.5});  // falls 0.2 m onto the first
  int joinedAt = -1;
  bool checked = false;
  int step = 0;
  world.setProblemObserver([&](std::int32_t, const solvers::ContactProblem& problem) {
    if (checked || problem.contactCount() < 8) return;  // the ground's 4 and the landing box's 4
    checked = true;
    joinedAt = step;
    ASSERT_TRUE(problem.warmStart.has_value()) << "step " << step;
    const Eigen::VectorXd& warm = *problem.warmStart;
    int loaded = 0, zero = 0;
    for (int c = 0; c < problem.contactCount(); ++c) {
      if (warm[3 * c] > 0.0) ++loaded;
      if (warm.segment<3>(3 * c).isZero(0.0)) ++zero;
    }
    EXPECT_EQ(loaded, 4) << "the resting box's ground contacts carry its weight";
    EXPECT_EQ(zero, 4) << "the new contacts start at zero";
  });
  for (; step < 60 && !checked; ++step) world.step(0.01);
  EXPECT_TRUE(checked);
  EXPECT_GT(joinedAt, 5);  // the first box had rested for a few steps by then
}
