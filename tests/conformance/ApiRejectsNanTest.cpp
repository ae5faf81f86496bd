// Issue 7 item 10: a NaN (or infinity) injected through the API is rejected with a CoulombError,
// not propagated: the state is unchanged and the scene keeps stepping to finite values.
#include <gtest/gtest.h>
#include <coulomb/engine/CoulombError.hpp>
#include <coulomb/engine/World.hpp>

#include "scenes/SceneRegistry.hpp"

#include <limits>

using namespace coulomb;

namespace {
constexpr double kNan = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();
}  // namespace

TEST(ApiRejectsNan, VelocitiesForcesAndStepsWithNonFiniteValuesAreRefused) {
  engine::World world = engine::io::buildWorld(scenes::loadBuiltinScene("box_stack_10"));
  for (int k = 0; k < 5; ++k) world.step();
  const geometry::BodyId box = world.findBody("box5");
  const std::uint64_t before = world.stateHash();
  const Eigen::Vector3d bad(0.0, kNan, 0.0);
  EXPECT_THROW(world.setVelocity(box, bad, Eigen::Vector3d::Zero()), engine::CoulombError);
  EXPECT_THROW(world.setVelocity(box, Eigen::Vector3d::Zero(), Eigen::Vector3d::Constant(kInf)),
               engine::CoulombError);
  EXPECT_THROW(world.applyForce(box, bad), engine::CoulombError);
  EXPECT_THROW(world.applyForceAtPoint(box, Eigen::Vector3d::UnitX(), bad), engine::CoulombError);
  EXPECT_THROW(world.applyTorque(box, bad), engine::CoulombError);
  EXPECT_THROW(world.setGravity(bad), engine::CoulombError);
  EXPECT_THROW(world.step(kNan), engine::CoulombError);
  EXPECT_EQ(world.stateHash(), before);  // nothing was half-applied

  for (int k = 0; k < 50; ++k) world.step();
  for (std::size_t i = 0; i < world.state().size(); ++i) {
    EXPECT_TRUE(world.state().poses[i].position.allFinite()) << "body " << i;
    EXPECT_TRUE(world.state().linearVelocities[i].allFinite()) << "body " << i;
  }
  EXPECT_LT((world.pose(box).position - Eigen::Vector3d(0, 0, 1.1)).norm(), 1e-3);
}

TEST(ApiRejectsNan, ABodyWithANonFinitePoseOrVelocityIsNotCreated) {
  engine::World world = engine::io::buildWorld(scenes::loadBuiltinScene("box_on_plane"));
  engine::io::Scene scene = scenes::loadBuiltinScene("box_on_plane");
  engine::BodyDesc desc = scene.bodies.back();
  desc.linearVelocity.x() = kNan;
  EXPECT_THROW(world.createBody(desc), engine::CoulombError);
  desc = scene.bodies.back();
  desc.pose.position.z() = kInf;
  EXPECT_THROW(world.createBody(desc), engine::CoulombError);
  EXPECT_EQ(world.bodyCount(), 2u);
}
