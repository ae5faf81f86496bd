// URDF robots in the World (urdf/UrdfLoader toArticulationDesc): r2d2 with a floating base
// (its corpus collision shapes: boxes, cylinders, a sphere, DAE gripper meshes) dropped onto a
// floor comes to rest on it; kuka_iiwa (STL hulls, fixed base) swings under gravity.
#include <coulomb/engine/World.hpp>
#include <coulomb/urdf/UrdfLoader.hpp>

#include <gtest/gtest.h>

#include <iostream>
#include <string>

namespace {

using namespace coulomb;
using engine::io::UrdfOptions;

std::string corpus(const std::string& relative) {
  return std::string(COULOMB_TEST_DATA_DIR) + "/urdf/" + relative;
}

void addFloor(engine::World& world) {
  engine::BodyDesc floor;
  floor.name = "floor";
  floor.motionType = geometry::MotionType::Static;
  floor.shapes.push_back({geometry::Plane{}, geometry::Pose::identity(), {0.8, 0.0}, {}});
  world.createBody(floor);
}

TEST(UrdfWorld, FloatingR2d2FallsOntoTheFloorAndStops) {
  engine::World world;
  addFloor(world);
  UrdfOptions options;
  options.base = engine::io::UrdfBase::Floating;
  options.basePose = geometry::Pose::translation({0.0, 0.0, 1.2});
  const auto model = engine::io::loadUrdfFile(corpus("r2d2/07-physics.urdf"), options);
  const auto id = world.createArticulation(engine::io::toArticulationDesc(model, "r2d2"));
  for (int step = 0; step < 300; ++step) world.step(0.005);
  const Eigen::VectorXd& q = world.articulations().q(id);
  ASSERT_TRUE(q.allFinite());
  // Fell from 1.2 m and rests on its wheels: the base above the floor, below where it started,
  // and (nearly) at rest.
  const double z = world.articulations().linkPose(id, 0).position.z();
  std::cout << "r2d2 base z after 1.5 s: " << z << " m\n";
  EXPECT_GT(z, 0.2) << "fell through the floor";
  EXPECT_LT(z, 1.0) << "did not fall";
  EXPECT_LT(world.articulations().qd(id).head<6>().norm(), 0.5);
}

TEST(UrdfWorld, FixedKukaSwingsUnderGravityWithFiniteState) {
  engine::World world;
  const auto model = engine::io::loadUrdfFile(corpus("kuka_iiwa/model.urdf"));
  const auto id = world.createArticulation(engine::io::toArticulationDesc(model, "kuka"));
  Eigen::VectorXd q = world.articulations().q(id);
  q[1] = 0.5;  // lean joint 2 so that gravity has a lever arm
  world.setArticulationState(id, q, Eigen::VectorXd::Zero(q.size()));
  for (int step = 0; step < 100; ++step) world.step(0.002);
  ASSERT_TRUE(world.articulations().q(id).allFinite());
  EXPECT_GT(world.articulations().q(id)[1], 0.55);  // fell further over
}

}  // namespace
