#include <gtest/gtest.h>
#include <coulomb/engine/CoulombError.hpp>
#include <coulomb/engine/World.hpp>

#include <cmath>

using namespace coulomb;
using engine::BodyDesc;
using engine::World;
using geometry::MotionType;

namespace {
BodyDesc ball(const std::string& name, const Eigen::Vector3d& position) {
  BodyDesc desc;
  desc.name = name;
  desc.pose.position = position;
  desc.shapes.push_back({geometry::Sphere{0.1}, {}, {}, {}});
  return desc;
}
}  // namespace

TEST(World, ProjectileFollowsTheClosedFormOfSemiImplicitEuler) {
  World world;
  BodyDesc desc = ball("ball", Eigen::Vector3d::Zero());
  desc.linearVelocity = Eigen::Vector3d(3.0, 0.0, 4.0);
  const auto id = world.createBody(desc);
  const double h = 0.01;
  for (int i = 0; i < 100; ++i) world.step(h);
  const double t = 1.0;
  const Eigen::Vector3d g = world.settings().gravity;
  // x_n = v0 t + g t^2 / 2 + g h t / 2: the closed form plus the method's known O(h) offset.
  const Eigen::Vector3d expected = desc.linearVelocity * t + 0.5 * g * t * t + 0.5 * g * h * t;
  EXPECT_LT((world.pose(id).position - expected).norm(), 1e-12);
  EXPECT_NEAR(world.time(), 1.0, 1e-12);
  EXPECT_EQ(world.stepCount(), 100u);
}

TEST(World, StaticAndKinematicBodiesIgnoreGravity) {
  World world;
  BodyDesc floor;
  floor.motionType = MotionType::Static;
  floor.shapes.push_back({geometry::Plane{}, {}, {}, {}});
  BodyDesc conveyor = ball("conveyor", Eigen::Vector3d::Zero());
  conveyor.motionType = MotionType::Kinematic;
  conveyor.linearVelocity = Eigen::Vector3d(1, 0, 0);
  const auto f = world.createBody(floor);
  const auto k = world.createBody(conveyor);
  const engine::StepReport report = world.step(0.5);
  EXPECT_EQ(report.dynamicBodies, 0u);
  EXPECT_EQ(report.kinematicBodies, 1u);
  EXPECT_EQ(world.pose(f).position, Eigen::Vector3d::Zero());
  EXPECT_TRUE(world.pose(k).position.isApprox(Eigen::Vector3d(0.5, 0, 0)));
  EXPECT_EQ(world.colliders().size(), 2u);
}

TEST(World, ForcesAndTorquesActForOneStep) {
  engine::WorldSettings noGravity;
  noGravity.gravity.setZero();
  World world(noGravity);
  BodyDesc desc;
  desc.mass = geometry::SpatialInertia{2.0, Eigen::Vector3d::Zero(), Eigen::Matrix3d::Identity()};
  const auto id = world.createBody(desc);
  world.applyForceAtPoint(id, Eigen::Vector3d(0, 4, 0), Eigen::Vector3d(1, 0, 0));
  world.step(0.5);
  EXPECT_TRUE(world.linearVelocity(id).isApprox(Eigen::Vector3d(0, 1, 0)));
  EXPECT_TRUE(world.angularVelocity(id).isApprox(Eigen::Vector3d(0, 0, 2)));  // tau = 4 z
  world.step(0.5);  // accumulators were cleared
  EXPECT_TRUE(world.linearVelocity(id).isApprox(Eigen::Vector3d(0, 1, 0)));
  world.applyTorque(id, Eigen::Vector3d(0, 0, -4));
  world.step(0.5);
  EXPECT_NEAR(world.angularVelocity(id).norm(), 0.0, 1e-12);
}

TEST(World, BodyFrameIsTheCentreOfMass) {
  World world;
  BodyDesc desc;
  desc.pose.position = Eigen::Vector3d(10, 0, 0);
  desc.shapes.push_back({geometry::Box{}, geometry::Pose::translation({1, 0, 0}), {}, {}});
  desc.shapes.push_back({geometry::Box{}, geometry::Pose::translation({3, 0, 0}), {}, {}});
  const auto id = world.createBody(desc);
  EXPECT_TRUE(world.pose(id).position.isApprox(Eigen::Vector3d(12, 0, 0)));
  EXPECT_NEAR(world.massProperties(id).mass, 2000.0, 1e-9);
  EXPECT_TRUE(world.colliders()[0].localPose.position.isApprox(Eigen::Vector3d(-1, 0, 0)));
  EXPECT_TRUE(world.colliders()[1].localPose.position.isApprox(Eigen::Vector3d(1, 0, 0)));
}

TEST(World, HandlesAreGenerationChecked) {
  World world;
  const auto a = world.createBody(ball("a", Eigen::Vector3d::Zero()));
  const auto b = world.createBody(ball("b", Eigen::Vector3d(1, 0, 0)));
  world.removeBody(a);
  EXPECT_FALSE(world.contains(a));
  EXPECT_THROW((void)world.pose(a), engine::CoulombError);
  EXPECT_EQ(world.colliders().size(), 1u);
  const auto c = world.createBody(ball("c", Eigen::Vector3d(2, 0, 0)));
  EXPECT_EQ(c.index, a.index);            // slot reused ...
  EXPECT_NE(c.generation, a.generation);  // ... under a new generation
  EXPECT_FALSE(world.contains(a));
  EXPECT_TRUE(world.contains(b));
  EXPECT_EQ(world.findBody("c"), c);
  EXPECT_EQ(world.bodyCount(), 2u);
  EXPECT_FALSE(world.findBody("a").valid());
}

TEST(World, BadStepAndSettingsAreErrors) {
  World world;
  EXPECT_THROW(world.step(0.0), engine::CoulombError);
  EXPECT_THROW(world.step(std::nan("")), engine::CoulombError);
  engine::WorldSettings bad;
  bad.timeStep = -1.0;
  EXPECT_THROW(World{bad}, engine::CoulombError);
  const auto id = world.createBody(ball("a", Eigen::Vector3d::Zero()));
  EXPECT_THROW(world.applyForce(id, Eigen::Vector3d(NAN, 0, 0)), engine::CoulombError);
  EXPECT_THROW(world.setGravity(Eigen::Vector3d(INFINITY, 0, 0)), engine::CoulombError);
}

TEST(World, StateHashIsReproducible) {
  auto run = [] {
    World world;
    BodyDesc desc = ball("spinner", Eigen::Vector3d::Zero());
    desc.shapes[0].shape = geometry::Box{Eigen::Vector3d(0.1, 0.2, 0.3)};
    desc.angularVelocity = Eigen::Vector3d(1.0, 5.0, 0.1);
    world.createBody(desc);
    for (int i = 0; i < 500; ++i) world.step();
    return world.stateHash();
  };
  EXPECT_EQ(run(), run());
}

TEST(World, MechanicalEnergyIsKineticPlusPotentialOfTheDynamicBodies) {
  // m = 2 kg at (1, 2, 3) m, v = (1, 0, 0) m/s, w = (0, 0, 2) rad/s about a principal axis with
  // I_z = 0.3 kg m^2: E = 1/2 2 1 + 1/2 0.3 4 + 2 9.81 3 = 60.46 J; a static body adds nothing.
  engine::World world;
  BodyDesc desc;
  desc.pose = geometry::Pose::translation({1.0, 2.0, 3.0});
  desc.linearVelocity = Eigen::Vector3d(1.0, 0.0, 0.0);
  desc.angularVelocity = Eigen::Vector3d(0.0, 0.0, 2.0);
  desc.mass = geometry::SpatialInertia{2.0, Eigen::Vector3d::Zero(),
                                       Eigen::Vector3d(0.1, 0.2, 0.3).asDiagonal()};
  world.createBody(desc);
  BodyDesc wall = ball("wall", Eigen::Vector3d(0.0, 0.0, 50.0));
  wall.motionType = geometry::MotionType::Static;
  world.createBody(wall);
  EXPECT_NEAR(world.mechanicalEnergy(), 60.46, 1e-12);
  // Gravity along -y: the potential is -m g.p = 2 * 5 * 2 = 20 J.
  world.setGravity(Eigen::Vector3d(0.0, -5.0, 0.0));
  EXPECT_NEAR(world.mechanicalEnergy(), 1.6 + 20.0, 1e-12);
}
