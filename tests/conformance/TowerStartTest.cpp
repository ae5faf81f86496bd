// A standing tower in the World (box_stack_20: 20 boxes, 80 contacts, 240 unknowns, nu = 2, so
// the automatic rules give it to ac_newton) never needs a Newton iteration after its first step:
// when its warm start misses the tolerance, the all-sticking start is tried before Newton's first
// iteration and is exact on a tower at rest (docs/solvers.md "Sticking start"). Without the
// sticking start the same tower takes a Newton iteration on about one step in eight.
#include <gtest/gtest.h>
#include <coulomb/engine/World.hpp>

#include "scenes/SceneRegistry.hpp"

#include <string>

using namespace coulomb;

TEST(TowerStart, AStandingTowerNeedsNoNewtonIterationAfterItsFirstStep) {
  for (const bool sticking : {true, false}) {
    engine::io::Scene scene = scenes::loadBuiltinScene("box_stack_20");
    scene.settings.solve.options.stickingStart = sticking;
    engine::World world = engine::io::buildWorld(scene);
    int iterations = 0, starts = 0;
    for (int step = 0; step < 300; ++step) {
      const engine::StepReport& report = world.step(scene.settings.timeStep);
      for (const engine::IslandReport& island : report.islands) {
        ASSERT_EQ(island.status, solvers::SolverStatus::Converged) << step;
        EXPECT_LE(island.solve.residual, 1e-6) << step;
        if (step == 0) continue;  // the cold start of the fresh tower
        for (const solvers::SolverReport& attempt : island.attempts) {
          EXPECT_EQ(attempt.solver, "ac_newton") << step;
          iterations += attempt.iterations;
        }
        if (island.solve.message.find("sticking start") != std::string::npos) ++starts;
      }
    }
    if (sticking) {
      EXPECT_EQ(iterations, 0);
      EXPECT_GT(starts, 0);
    } else {
      // Measured: 36 in 299 steps (about one every other step before the steady warm start, which
      // keeps each Newton answer's load for the next step: docs/solvers.md "Steady warm start").
      EXPECT_GT(iterations, 10);
      EXPECT_EQ(starts, 0);
    }
  }
}
