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
