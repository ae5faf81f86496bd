// Snapshots (io/Snapshot): continuing from a snapshot gives the bit-identical trajectory of
// the uninterrupted run (issue 13 item 3), on contact stacks, joints and URDF robots; a bad,
// truncated or mismatched snapshot is a CoulombError naming the file and leaves the World as it
// was.
#include <gtest/gtest.h>
#include <coulomb/engine/CoulombError.hpp>
#include <coulomb/engine/World.hpp>
#include <coulomb/io/Snapshot.hpp>

#include "scenes/SceneRegistry.hpp"

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

using namespace coulomb;
namespace io = coulomb::engine::io;

namespace {

struct Horizon {
  const char* scene;
  int before;  // steps before the snapshot
  int after;   // steps after it, in both runs
};

#ifdef COULOMB_SANITIZE
constexpr int kScale = 4;  // ASan/UBSan runs 3-5x slower
#else
constexpr int kScale = 1;
#endif

std::filesystem::path tempFile(const std::string& name) {
  return std::filesystem::path(COULOMB_BINARY_DIR) / ("snapshot_test_" + name + ".snap");
}

/// Every double of every body's pose and velocities, bit for bit.
void expectSameBodies(const engine::World& a, const engine::World& b, const std::string& what) {
  ASSERT_EQ(a.state().size(), b.state().size()) << what;
  for (std::size_t i = 0; i < a.state().size(); ++i) {
    const auto& pa = a.state().poses[i];
    const auto& pb = b.state().poses[i];
    EXPECT_EQ(0, std::memcmp(pa.position.data(), pb.position.data(), 3 * sizeof(double)))
        << what << " body " << i;
    EXPECT_EQ(0, std::memcmp(pa.rotation.coeffs().data(), pb.rotation.coeffs().data(),
                             4 * sizeof(double)))
        << what << " body " << i;
    EXPECT_EQ(0, std::memcmp(a.state().linearVelocities[i].data(),
                             b.state().linearVelocities[i].data(), 3 * sizeof(double)))
        << what << " body " << i;
    EXPECT_EQ(0, std::memcmp(a.state().angularVelocities[i].data(),
                             b.state().angularVelocities[i].data(), 3 * sizeof(double)))
        << what << " body " << i;
  }
}

class SnapshotContinuation : public ::testing::TestWithParam<Horizon> {};

}  // namespace

TEST_P(SnapshotContinuation, RestoredRunIsBitIdenticalToTheUninterruptedOne) {
  const Horizon hz = GetParam();
  const int before = std::max(1, hz.before / kScale), after = std::max(2, hz.after / kScale);
  const engine::io::Scene scene = scenes::loadBuiltinScene(hz.scene);
  engine::World original = engine::io::buildWorld(scene);
  for (int n = 0; n < before; ++n) original.step();
  const std::filesystem::path file = tempFile(hz.scene);
  io::saveSnapshotFile(original, file);
  std::printf("%s: snapshot of %zu bytes\n", hz.scene,
              static_cast<std::size_t>(std::filesystem::file_size(file)));
  for (int n = 0; n < after; ++n) original.step();

  engine::World restored = engine::io::buildWorld(scene);
  io::loadSnapshotFile(restored, file);
  EXPECT_EQ(restored.stepCount(), static_cast<std::uint64_t>(before));
  for (int n = 0; n < after; ++n) restored.step();

  expectSameBodies(original, restored, hz.scene);
  EXPECT_EQ(original.stateHash(), restored.stateHash());
  EXPECT_EQ(original.time(), restored.time());
  EXPECT_EQ(original.stepCount(), restored.stepCount());
  // The snapshots of the two end states are the same bytes: warm starts, contact cache, joints,
  // trees, sleep timers and settings agree too, not only the poses.
  EXPECT_TRUE(io::saveSnapshot(original) == io::saveSnapshot(restored)) << hz.scene;
  // The state did move after the snapshot (the comparison is not vacuous).
  engine::World atSnapshot = engine::io::buildWorld(scene);
  io::loadSnapshotFile(atSnapshot, file);
  EXPECT_NE(atSnapshot.stateHash(), original.stateHash());
  std::filesystem::remove(file);
}

INSTANTIATE_TEST_SUITE_P(BuiltinScenes, SnapshotContinuation,
                         ::testing::Values(Horizon{"pyramid_10", 20, 20},
                                           Horizon{"anymal_standing", 20, 20},
                                           Horizon{"kuka_swing_into_boxes", 30, 30},
                                           Horizon{"chain_10", 40, 40},
                                           Horizon{"box_stack_10", 40, 40}),
                         [](const auto& info) { return std::string(info.param.scene); });

TEST(Snapshot, ALimpRobotWithJointFrictionContinuesBitForBit) {
  // anymal_standing without its motors and with 2 N m of dry friction in every 1-DOF joint:
  // the friction rows act (and warm start) while the robot sags.
  engine::io::Scene scene = scenes::loadBuiltinScene("anymal_standing");
  ASSERT_FALSE(scene.articulations.empty());
  int withFriction = 0;
  for (engine::ArticulationDesc& a : scene.articulations) {
    a.motors.clear();
    for (engine::ArticulationLinkDesc& link : a.links)
      if (link.joint.nv() == 1) {
        link.jointFriction = 2.0;
        ++withFriction;
      }
  }
  ASSERT_GT(withFriction, 0);
  engine::World original = engine::io::buildWorld(scene);
  for (int n = 0; n < 15; ++n) original.step();
  const std::vector<std::uint8_t> bytes = io::saveSnapshot(original);
  for (int n = 0; n < 15; ++n) original.step();
  engine::World restored = engine::io::buildWorld(scene);
  io::restoreSnapshot(restored, bytes);
  for (int n = 0; n < 15; ++n) restored.step();
  expectSameBodies(original, restored, "limp anymal");
  EXPECT_TRUE(io::saveSnapshot(original) == io::saveSnapshot(restored));
}

TEST(Snapshot, SleepStateAndTimersAreRestored) {
  engine::io::Scene scene = scenes::loadBuiltinScene("box_stack_10");
  scene.settings.sleep.enabled = true;
  scene.settings.sleep.timeToSleep = 0.05;  // the stack falls asleep within the horizon
  engine::World original = engine::io::buildWorld(scene);
  for (int n = 0; n < 60; ++n) original.step();
  const std::vector<std::uint8_t> bytes = io::saveSnapshot(original);
  engine::World restored = engine::io::buildWorld(scene);
  io::restoreSnapshot(restored, bytes);
  // Wake the stack in both: the top box gets a push.
  const geometry::BodyId top = original.idAt(original.state().size() - 1);
  for (engine::World* w : {&original, &restored}) {
    w->setVelocity(top, Eigen::Vector3d(0.3, 0.0, 0.0), Eigen::Vector3d::Zero());
    for (int n = 0; n < 20; ++n) w->step();
  }
  expectSameBodies(original, restored, "sleep");
  EXPECT_TRUE(io::saveSnapshot(original) == io::saveSnapshot(restored));
}

TEST(Snapshot, SettingsChangedThroughTheApiAreRestored) {
  const engine::io::Scene scene = scenes::loadBuiltinScene("box_stack_10");
  engine::World original = engine::io::buildWorld(scene);
  original.setGravity(Eigen::Vector3d(0.0, 1.0, -5.0));
  coulomb::solvers::SolvePolicy policy = original.settings().solve;
  policy.choice = coulomb::solvers::SolverChoice::chain({"pgs", "ac_newton"});
  policy.choice.attempts[0].maxIterations = 7;
  policy.chooser.pileNu = 1.25;
  policy.promotion.nearMiss = 3.0;
  policy.options.sweepPartBlocks = 77;
  policy.options.stickingStart = false;
  original.setSolvePolicy(policy);
  original.setSolverOverride(original.idAt(1), coulomb::solvers::SolverChoice::only("bgs"));
  original.step();
  engine::World restored = engine::io::buildWorld(scene);
  io::restoreSnapshot(restored, io::saveSnapshot(original));
  EXPECT_EQ(restored.settings().gravity, Eigen::Vector3d(0.0, 1.0, -5.0));
  EXPECT_EQ(restored.settings().solve.choice, policy.choice);
  EXPECT_EQ(restored.settings().solve.chooser, policy.chooser);
  EXPECT_EQ(restored.settings().solve.promotion, policy.promotion);
  EXPECT_EQ(restored.settings().solve.options.sweepPartBlocks, 77);
  EXPECT_FALSE(restored.settings().solve.options.stickingStart);
  // and the per-body choice: both worlds solve the next step alike
  EXPECT_EQ(original.step().islands.front().reason(), restored.step().islands.front().reason());
  EXPECT_EQ(original.stateHash(), restored.stateHash());
}

TEST(Snapshot, TheTreeIntegratorIsRestoredAndATreeContinuesBitForBit) {
  const engine::io::Scene scene = scenes::loadBuiltinScene("pendulum_reduced");
  for (const engine::TreeIntegrator integrator :
       {engine::TreeIntegrator::RungeKutta, engine::TreeIntegrator::SemiImplicitEuler}) {
    engine::World original = engine::io::buildWorld(scene);
    engine::WorldSettings settings = original.settings();
    settings.treeIntegrator = integrator;
    original.setSettings(settings);
    for (int k = 0; k < 30; ++k) original.step();
    engine::World restored = engine::io::buildWorld(scene);  // the scene's default integrator
    io::restoreSnapshot(restored, io::saveSnapshot(original));
    EXPECT_EQ(restored.settings().treeIntegrator, integrator);
    for (int k = 0; k < 50; ++k) {
      original.step();
      restored.step();
    }
    EXPECT_EQ(original.stateHash(), restored.stateHash());
  }
}

namespace {
/// Restoring `bytes` into a box_stack_10 world throws a CoulombError whose message holds `expected`
/// and the source name, and leaves the world exactly as it was.
void expectRejected(const std::vector<std::uint8_t>& bytes, const std::string& expected) {
  engine::World world = engine::io::buildWorld(scenes::loadBuiltinScene("box_stack_10"));
  for (int n = 0; n < 3; ++n) world.step();
  const std::vector<std::uint8_t> before = io::saveSnapshot(world);
  try {
    io::restoreSnapshot(world, bytes, "my.snap");
    ADD_FAILURE() << "accepted a bad snapshot (" << expected << ")";
  } catch (const engine::CoulombError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("my.snap"), std::string::npos) << message;
    EXPECT_NE(message.find(expected), std::string::npos) << message;
  }
  EXPECT_TRUE(io::saveSnapshot(world) == before) << "the world changed (" << expected << ")";
}

std::vector<std::uint8_t> stackSnapshot(int steps) {
  engine::World world = engine::io::buildWorld(scenes::loadBuiltinScene("box_stack_10"));
  for (int n = 0; n < steps; ++n) world.step();
  return io::saveSnapshot(world);
}
}  // namespace

TEST(Snapshot, BadSnapshotsAreRejectedByNameAndLeaveTheWorldUnchanged) {
  const std::vector<std::uint8_t> good = stackSnapshot(2);
  expectRejected({}, "not a Coulomb snapshot");
  std::vector<std::uint8_t> magic = good;
  magic[0] = 'X';
  expectRejected(magic, "bad magic");
  std::vector<std::uint8_t> version = good;
  version[8] = 99;
  expectRejected(version, "format version 99");
  for (const std::size_t keep : {good.size() / 2, good.size() - 1}) {
    const std::vector<std::uint8_t> truncated(good.begin(), good.begin() + keep);
    expectRejected(truncated, "truncated");
  }
  std::vector<std::uint8_t> flipped = good;
  flipped[good.size() / 2] ^= 0x10;
  expectRejected(flipped, "checksum");
}

TEST(Snapshot, ASnapshotOfAnotherSceneIsRejected) {
  engine::World other = engine::io::buildWorld(scenes::loadBuiltinScene("box_on_plane"));
  other.step();
  expectRejected(io::saveSnapshot(other), "does not match this world");
  // Same slot count, another structure: a world whose last body was removed.
  engine::World removed = engine::io::buildWorld(scenes::loadBuiltinScene("box_stack_10"));
  removed.removeBody(removed.idAt(removed.state().size() - 1));
  expectRejected(io::saveSnapshot(removed), "does not match this world");
}

TEST(Snapshot, MissingFileIsNamed) {
  engine::World world = engine::io::buildWorld(scenes::loadBuiltinScene("box_on_plane"));
  try {
    io::loadSnapshotFile(world, tempFile("does_not_exist"));
    FAIL() << "no error";
  } catch (const engine::CoulombError& e) {
    EXPECT_NE(std::string(e.what()).find("does_not_exist"), std::string::npos) << e.what();
  }
}
