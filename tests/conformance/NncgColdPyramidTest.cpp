// nncg and bgs_nncg (pgs and bgs sweeps with nonsmooth nonlinear conjugate-gradient momentum,
// Silcowski, Erleben et al. 2015; solvers/GaussSeidelLoop.hpp) on the hardest Gauss-Seidel
// problem of the scenes: the first step of a fresh pyramid_10, where only the ground row
// approaches (q_N < 0) and the load must travel up ten rows of contacts. From zero plain bgs needs
// about 3 800 sweeps and plain pgs is still at 5e-6 after 5 000 (measured); with momentum 365 and
// 910. All run on the same problem captured from the World (body-space W).
#include <gtest/gtest.h>
#include <coulomb/engine/World.hpp>
#include <coulomb/solvers/ContactSolver.hpp>
#include <coulomb/solvers/SolverRegistry.hpp>

#include "scenes/SceneRegistry.hpp"

#include <algorithm>
#include <optional>

using namespace coulomb;

namespace {

solvers::ContactProblem firstPyramidProblem() {
  const engine::io::Scene scene = scenes::loadBuiltinScene("pyramid_10");
  engine::World world = engine::io::buildWorld(scene);
  std::optional<solvers::ContactProblem> captured;
  world.setProblemObserver([&captured](std::int32_t, const solvers::ContactProblem& problem) {
    if (!captured || problem.size() > captured->size()) captured = problem;
  });
  world.step(scene.settings.timeStep);
  EXPECT_TRUE(captured.has_value());
  return captured ? *captured : solvers::ContactProblem{};
}

solvers::SolverReport solveWith(const std::string& name, const solvers::ContactProblem& problem,
                                int sweeps) {
  const auto solver = solvers::SolverRegistry::builtIn().create(name);
  solvers::SolverOptions options;
  options.maxIterations = sweeps;
  options.tolerance = 1e-6;
  options.useWarmStart = false;
  return solver->solve(problem, options).report;
}

}  // namespace

TEST(NncgColdPyramid, MomentumConvergesWherePlainSweepsDoNot) {
  const solvers::ContactProblem problem = firstPyramidProblem();
  ASSERT_EQ(problem.size(), 1200);  // 100 box-box and box-ground faces, 4 points each
  struct Pair {
    const char *accelerated, *plain;
    int budget, expectedAtMost;  // sweeps given; sweeps the accelerated one may take
  };
  for (const Pair& pair : {Pair{"bgs_nncg", "bgs", 1000, 600}, Pair{"nncg", "pgs", 1500, 1200}}) {
    const solvers::SolverReport fast = solveWith(pair.accelerated, problem, pair.budget);
    const solvers::SolverReport slow = solveWith(pair.plain, problem, pair.budget);
    std::printf("cold pyramid_10: %s %d sweeps, residual %.3g; %s %d sweeps, residual %.3g\n",
                pair.accelerated, fast.iterations, fast.residual, pair.plain, slow.iterations,
                slow.residual);
    EXPECT_EQ(fast.status, solvers::SolverStatus::Converged) << pair.accelerated;
    EXPECT_LE(fast.residual, 1e-6) << pair.accelerated;
    EXPECT_LE(fast.iterations, pair.expectedAtMost) << pair.accelerated;
    EXPECT_NE(slow.status, solvers::SolverStatus::Converged) << pair.plain;
    EXPECT_GT(slow.residual, 5 * fast.residual) << pair.plain;
    // Deterministic: the same problem gives the same sweeps and answer.
    const solvers::SolverReport again = solveWith(pair.accelerated, problem, pair.budget);
    EXPECT_EQ(again.iterations, fast.iterations);
    EXPECT_EQ(again.residual, fast.residual);
  }
}

// The World's answer to the same first step (SolverOptions::stickingStart, on by default): the
// all-sticking start is the resting pyramid's exact answer, so no sweep is needed; without it the
// plan spends its 200 bgs_nncg sweeps and a Newton fallback. Both end within the tolerance.
TEST(NncgColdPyramid, TheWorldSolvesTheFirstStepAtItsStickingStart) {
  for (const bool sticking : {true, false}) {
    engine::io::Scene scene = scenes::loadBuiltinScene("pyramid_10");
    scene.settings.solve.options.stickingStart = sticking;
    engine::World world = engine::io::buildWorld(scene);
    const engine::StepReport& report = world.step(scene.settings.timeStep);
    const engine::IslandReport* largest = nullptr;
    for (const engine::IslandReport& island : report.islands)
      if (!largest || island.unknowns > largest->unknowns) largest = &island;
    ASSERT_NE(largest, nullptr);
    ASSERT_EQ(largest->unknowns, 1200);
    EXPECT_EQ(largest->status, solvers::SolverStatus::Converged) << sticking;
    EXPECT_LE(largest->solve.residual, 1e-6) << sticking;
    int sweeps = 0;
    for (const solvers::SolverReport& attempt : largest->attempts) sweeps += attempt.iterations;
    if (sticking) {
      EXPECT_EQ(sweeps, 0);
      EXPECT_EQ(largest->attempts.size(), 1u);
      EXPECT_NE(largest->solve.message.find("sticking start"), std::string::npos);
    } else {
      EXPECT_GE(sweeps, 200);
    }
    // The next step is warm-started everywhere: no sticking start is computed.
    for (const engine::IslandReport& island : world.step(scene.settings.timeStep).islands)
      EXPECT_EQ(island.solve.message.find("sticking start"), std::string::npos);
  }
}

// The restart (ContactSolver::kStickingRestartSweeps): a standing pyramid_10 whose warm start
// Gauss-Seidel cannot finish in two sweeps restarts from the all-sticking start, which is exact
// there, so no step sweeps more than twice. Without the sticking start the same scene has steps
// of tens of sweeps (50 at step 6 from its cold start, 20 around step 100).
TEST(NncgColdPyramid, AStandingPyramidNeverSweepsLongerThanItsStickingRestart) {
  for (const bool sticking : {true, false}) {
    engine::io::Scene scene = scenes::loadBuiltinScene("pyramid_10");
    scene.settings.solve.options.stickingStart = sticking;
    engine::World world = engine::io::buildWorld(scene);
    int most = 0, restarts = 0;
    for (int step = 0; step < 400; ++step) {
      const engine::StepReport& report = world.step(scene.settings.timeStep);
      for (const engine::IslandReport& island : report.islands) {
        ASSERT_EQ(island.status, solvers::SolverStatus::Converged) << step;
        EXPECT_LE(island.solve.residual, 1e-6) << step;
        int sweeps = 0;
        for (const solvers::SolverReport& attempt : island.attempts) sweeps += attempt.iterations;
        if (step > 0) most = std::max(most, sweeps);
        const bool restarted = island.solve.message.find("sticking start") != std::string::npos;
        if (step > 0 && restarted) {
          EXPECT_EQ(sweeps, solvers::ContactSolver::kStickingRestartSweeps) << step;
          ++restarts;
        }
      }
    }
    if (sticking) {
      EXPECT_LE(most, solvers::ContactSolver::kStickingRestartSweeps);
      EXPECT_GT(restarts, 0);
    } else {
      EXPECT_GE(most, 10);
      EXPECT_EQ(restarts, 0);
    }
  }
}
