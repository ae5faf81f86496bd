// engine/ImpactPropagation through the World: binary Newton impacts of unequal masses, a bounce
// off a static floor, and contacts left over by the sweep cap finishing in the velocity problem.
#include <gtest/gtest.h>
#include <coulomb/engine/World.hpp>

#include <vector>

using namespace coulomb;
using geometry::BodyId;

namespace {

engine::WorldSettings settings(engine::ImpactLaw law, int maxSweeps = 100) {
  engine::WorldSettings s;
  s.gravity.setZero();
  s.contact.impactLaw = law;
  s.contact.maxImpactSweeps = maxSweeps;
  s.solve.options.tolerance = 1e-12;  // the simultaneous law's answer to round-off
  return s;
}

// A frictionless ball of radius 0.05 with restitution e.
BodyId addBall(engine::World& world, double x, double mass, double vx, double e) {
  engine::BodyDesc ball;
  ball.name = "ball";
  ball.pose = geometry::Pose::translation({x, 0.0, 0.0});
  ball.linearVelocity = {vx, 0.0, 0.0};
  ball.shapes.push_back({geometry::Sphere{0.05}, {}, {0.0, e}, {}});
  ball.mass = geometry::SpatialInertia{mass, Eigen::Vector3d::Zero(),
                                       Eigen::Matrix3d::Identity() * 0.4 * mass * 0.0025};
  return world.createBody(ball);
}

}  // namespace

// Newton's law for two bodies (survey sec. 2.1.6): v1' = (m1 - e m2) v / (m1 + m2),
// v2' = (1 + e) m1 v / (m1 + m2). One contact: both laws agree.
TEST(ImpactPropagation, UnequalMassesFollowNewtonsLaw) {
  for (const engine::ImpactLaw law :
       {engine::ImpactLaw::Propagating, engine::ImpactLaw::Simultaneous})
    for (const double e : {1.0, 0.5}) {
      engine::World world(settings(law));
      const BodyId a = addBall(world, -0.1, 1.0, 1.0, e);  // touching b
      const BodyId b = addBall(world, 0.0, 3.0, 0.0, e);
      world.step(0.01);
      EXPECT_NEAR(world.linearVelocity(a).x(), (1.0 - 3.0 * e) / 4.0, 1e-9) << e;
      EXPECT_NEAR(world.linearVelocity(b).x(), (1.0 + e) / 4.0, 1e-9) << e;
    }
}

// A static body has infinite mass: the ball leaves with -e times its approach speed.
TEST(ImpactPropagation, BallBouncesOffAStaticFloor) {
  engine::World world(settings(engine::ImpactLaw::Propagating));
  engine::BodyDesc floor;
  floor.name = "floor";
  floor.motionType = geometry::MotionType::Static;
  floor.shapes.push_back({geometry::Plane{}, {}, {0.0, 0.5}, {}});
  world.createBody(floor);
  engine::BodyDesc ball;
  ball.name = "ball";
  ball.pose = geometry::Pose::translation({0.0, 0.0, 0.05});  // touching
  ball.linearVelocity = {0.0, 0.0, -2.0};
  ball.shapes.push_back({geometry::Sphere{0.05}, {}, {0.0, 0.5}, {}});
  ball.mass =
      geometry::SpatialInertia{1.0, Eigen::Vector3d::Zero(), Eigen::Matrix3d::Identity() * 0.001};
  const BodyId id = world.createBody(ball);
  world.step(0.01);
  EXPECT_NEAR(world.linearVelocity(id).z(), 1.0, 1e-12);
}

// Three equal touching balls created right to left, so the island meets the far contact first:
// one sweep resolves only the striker's contact, and the cap (1 sweep) leaves the other to
// Newton's law in the velocity problem, which still hands the momentum on: (0, 0, 1).
TEST(ImpactPropagation, ContactsLeftByTheSweepCapFinishInTheVelocityProblem) {
  for (const int cap : {1, 100}) {
    engine::World world(settings(engine::ImpactLaw::Propagating, cap));
    const BodyId c = addBall(world, 0.1, 1.0, 0.0, 1.0);
    const BodyId b = addBall(world, 0.0, 1.0, 0.0, 1.0);
    const BodyId a = addBall(world, -0.1, 1.0, 1.0, 1.0);
    world.step(0.01);
    EXPECT_NEAR(world.linearVelocity(a).x(), 0.0, 1e-9) << cap;
    EXPECT_NEAR(world.linearVelocity(b).x(), 0.0, 1e-9) << cap;
    EXPECT_NEAR(world.linearVelocity(c).x(), 1.0, 1e-9) << cap;
  }
}
