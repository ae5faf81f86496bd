// docs/scene-specifications.md A4: the 55-box pyramid run twice from scratch gives bit-identical
// states after every step (golden rule 7: no unordered containers, no threads, no time-dependent
// choices in a step).
#include <gtest/gtest.h>
#include <coulomb/engine/World.hpp>

#include "scenes/SceneRegistry.hpp"

#include <cstdint>
#include <string>
#include <vector>

using namespace coulomb;

namespace {

#ifdef COULOMB_SANITIZE
constexpr int kSteps = 40;  // ASan/UBSan runs 3-5x slower; still many warm-started solves
#else
constexpr int kSteps = 200;
#endif

std::vector<std::uint64_t> hashesOfARun(const std::string& solver) {
  engine::io::Scene scene = scenes::loadBuiltinScene("pyramid_10");
  scene.settings.solve.choice = coulomb::solvers::solverChoice(solver);
  engine::World world = engine::io::buildWorld(scene);
  std::vector<std::uint64_t> hashes;
  for (int k = 0; k < kSteps; ++k) {
    world.step(scene.settings.timeStep);
    hashes.push_back(world.stateHash());
  }
  return hashes;
}

class PyramidDeterminism : public ::testing::TestWithParam<std::string> {};

}  // namespace

TEST_P(PyramidDeterminism, TwoRunsAreBitIdenticalAtEveryStep) {
  const std::vector<std::uint64_t> first = hashesOfARun(GetParam());
  const std::vector<std::uint64_t> second = hashesOfARun(GetParam());
  ASSERT_EQ(first.size(), second.size());
  for (std::size_t k = 0; k < first.size(); ++k)
    ASSERT_EQ(first[k], second[k]) << "states differ after step " << k;
  // The hash sees the motion: the boxes settle under gravity, so the state changes.
  EXPECT_NE(first.front(), first.back());
}

INSTANTIATE_TEST_SUITE_P(AutoAndPgs, PyramidDeterminism, ::testing::Values("auto", "pgs"));
