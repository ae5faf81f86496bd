// nncg (bgs sweeps with nonsmooth nonlinear conjugate-gradient momentum, Silcowski, Erleben et al.
// 2015; solvers/GaussSeidelLoop.hpp) on the hardest Gauss-Seidel problem of the scenes: the first
// step of a fresh pyramid_10, where only the ground row approaches (q_N < 0) and the load must
// travel up ten rows of contacts. Plain bgs needs about 3 800 sweeps from zero (measured), nncg a
// tenth of that; both run on the same problem captured from the World (body-space W).
#include <gtest/gtest.h>
#include <coulomb/engine/World.hpp>
#include <coulomb/solvers/SolverRegistry.hpp>

#include "scenes/SceneRegistry.hpp"

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

TEST(NncgColdPyramid, ConvergesWhereBgsStallsWithTheSameSweeps) {
  const solvers::ContactProblem problem = firstPyramidProblem();
  ASSERT_EQ(problem.size(), 1200);  // 100 box-box and box-ground faces, 4 points each
  const solvers::SolverReport nncg = solveWith("nncg", problem, 1000);
  const solvers::SolverReport bgs = solveWith("bgs", problem, 1000);
  std::printf("cold pyramid_10: nncg %d sweeps, residual %.3g; bgs %d sweeps, residual %.3g\n",
              nncg.iterations, nncg.residual, bgs.iterations, bgs.residual);
  EXPECT_EQ(nncg.status, solvers::SolverStatus::Converged);
  EXPECT_LE(nncg.residual, 1e-6);
  EXPECT_LE(nncg.iterations, 600);  // measured 365
  EXPECT_NE(bgs.status, solvers::SolverStatus::Converged);
  EXPECT_GT(bgs.residual, 10 * nncg.residual);
  // Deterministic: the same problem gives the same sweeps and answer.
  const solvers::SolverReport again = solveWith("nncg", problem, 1000);
  EXPECT_EQ(again.iterations, nncg.iterations);
  EXPECT_EQ(again.residual, nncg.residual);
}
