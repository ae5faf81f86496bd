// A steady step allocates nothing (docs/architecture.md, "Memory in the step"): every buffer of
// the step (step data, rows, problems, solver workspaces, the report) is kept by its World and
// reused, so once a scene's sizes have settled a step makes no heap allocation at all. Checked
// with the default policy where its solvers keep their workspaces (Gauss-Seidel, the Newton
// solvers' dense path), and with Gauss-Seidel forced on the stacks, whose occasional Newton
// fallback still allocates in Eigen's sparse LU (docs/benchmarks.md, "The step rebuilt").
// The count covers the whole process: glibc's malloc family is interposed by the heap counter
// linked into this test (samples/support/HeapCounter.hpp; operator new and Eigen both end there).
// Not built under AddressSanitizer, which owns the allocator.
#include <coulomb/engine/World.hpp>
#include <coulomb/io/SceneLoader.hpp>
#include <coulomb/solvers/SolvePolicy.hpp>

#include "scenes/SceneRegistry.hpp"
#include "support/HeapCounter.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <string>
#include <vector>

namespace coulomb {
namespace {

// Heap allocations made by `steps` steps of the built-in scene after `warmup` steps, solved by
// exactly `solver` (text form of the solve policy).
std::uint64_t allocationsOfSteadySteps(const std::string& name, const std::string& solver,
                                       int warmup, int steps,
                                       joints::EnergyTarget energy = joints::EnergyTarget::None) {
  engine::io::Scene scene = scenes::loadBuiltinScene(name);
  scene.settings.jointStabilization.predictedState.energy = energy;
  engine::World world = engine::io::buildWorld(scene);
  world.setSolver(solvers::solverChoice(solver));
  for (int k = 0; k < warmup; ++k) world.step(scene.settings.timeStep);
  const std::uint64_t before = support::heapAllocations();
  for (int k = 0; k < steps; ++k) world.step(scene.settings.timeStep);
  return support::heapAllocations() - before;
}

TEST(SteadyStepAllocation, TheCounterSeesContainersAndEigen) {
  const std::uint64_t before = support::heapAllocations();
  std::vector<double> v(100, 1.0);
  Eigen::VectorXd e = Eigen::VectorXd::Ones(100);
  EXPECT_GE(support::heapAllocations() - before, 2u);
  EXPECT_EQ(v.size() + static_cast<std::size_t>(e.size()), 200u);
}

TEST(SteadyStepAllocation, FirstStepsDoAllocate) {
  // The buffers are sized on the first steps: the count is not trivially zero.
  EXPECT_GT(allocationsOfSteadySteps("pyramid_10", "pgs!", 0, 1), 0u);
}

// A resting 55-box pyramid: broad and narrow phase, islands, body-space assembly (W factored),
// the plan, pgs, impulses, the split impulse's check, sleep, the report.
// Warmed up for 100 steps: the fresh pyramid rests on its sticking start without a sweep until
// step 53 (pgs!), and a solver's buffers are sized on its first sweep.
TEST(SteadyStepAllocation, RestingPyramidAllocatesNothing) {
  EXPECT_EQ(allocationsOfSteadySteps("pyramid_10", "pgs!", 100, 200), 0u);
  EXPECT_EQ(allocationsOfSteadySteps("pyramid_10", "auto", 100, 200), 0u);  // nncg first
}

// A 10-box tower: a dense-then-sparse block W of a narrow island, with bgs, then auto (ac_newton:
// the dense LU in place in storage sized to the island while the kept rows vary).
TEST(SteadyStepAllocation, TowerAllocatesNothing) {
  EXPECT_EQ(allocationsOfSteadySteps("box_stack_10", "bgs!", 50, 200), 0u);
  EXPECT_EQ(allocationsOfSteadySteps("box_stack_10", "auto", 100, 200), 0u);
}

// A masonry arch of convex hulls: hull-hull manifolds from the hulls' own faces (no per-query
// face building), in the narrow phase's kept scratch.
TEST(SteadyStepAllocation, HullArchAllocatesNothing) {
  EXPECT_EQ(allocationsOfSteadySteps("masonry_arch_mu0_6", "auto", 50, 200), 0u);
}

// One box held by friction on an incline: a dense one-contact island (bgs forced, then auto:
// ac_newton with its dense LU).
TEST(SteadyStepAllocation, BoxOnInclineAllocatesNothing) {
  EXPECT_EQ(allocationsOfSteadySteps("box_incline_A_stick", "bgs!", 50, 200), 0u);
  EXPECT_EQ(allocationsOfSteadySteps("box_incline_A_stick", "auto", 50, 200), 0u);
}

// Ball-jointed chains (maximal coordinates) with the predicted-state correction: the ldlt solve
// and the correction's LDL^T work in storage analysed once (warm-up past the first swing, whose
// broad-phase pair lists still grow).
TEST(SteadyStepAllocation, ChainsAllocateNothing) {
  EXPECT_EQ(allocationsOfSteadySteps("chain_10", "auto", 200, 300), 0u);
  EXPECT_EQ(allocationsOfSteadySteps("chain_50", "auto", 200, 300), 0u);
  // The energy projection: the bodies' start energies in the step's kept storage (a longer
  // warm-up: the chain keeps its energy, so its swings reach new broad-phase pairs later).
  EXPECT_EQ(allocationsOfSteadySteps("chain_10", "auto", 500, 300, joints::EnergyTarget::Modified),
            0u);
}

// Default policy on small scenes: a 1000:1 mass ratio (ac_newton), a sliding sphere, a cradle.
TEST(SteadyStepAllocation, SmallScenesWithAutoAllocateNothing) {
  for (const char* scene : {"mass_ratio_1000kg_on_1kg", "sphere_slide", "newton_cradle"})
    EXPECT_EQ(allocationsOfSteadySteps(scene, "auto", 100, 200), 0u) << scene;
}

// A quadruped standing on its feet (reduced coordinates): ABA's prediction, the proxies'
// kinematics, the trees' joint-space rows and impulse-level ABA in the assembly and the impulses,
// in kept per-tree storage; bgs forced, then auto (ac_newton with its stall restart and proximal
// loop, fb_newton as a fallback: every solver's storage is warm after 300 steps).
TEST(SteadyStepAllocation, StandingQuadrupedAllocatesNothing) {
  EXPECT_EQ(allocationsOfSteadySteps("anymal_standing", "bgs!", 100, 100), 0u);
  EXPECT_EQ(allocationsOfSteadySteps("anymal_standing", "auto", 300, 100), 0u);
}

}  // namespace
}  // namespace coulomb
