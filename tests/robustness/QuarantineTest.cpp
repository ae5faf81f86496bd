// The World-level guard (engine/Quarantine.hpp, issue 13 item 2): a body whose state becomes
// non-finite or leaves the sanity limits is isolated and reported, the rest keeps running
// untouched, and no NaN stays in the state.
#include <gtest/gtest.h>
#include <coulomb/engine/CoulombError.hpp>
#include <coulomb/engine/World.hpp>

#include "RobustnessScenes.hpp"
#include "scenes/SceneRegistry.hpp"

#include <cstring>
#include <string>

using namespace coulomb;
using robustness::box;
using robustness::ground;
using robustness::stateIsFinite;

namespace {

constexpr double kHuge = 1e308;  // finite; two of them add up to +inf

/// Forces and torques are checked one call at a time, so two finite calls overflow the
/// accumulators to +inf: the only way to a non-finite state through the public API.
void overflow(engine::World& world, geometry::BodyId id) {
  for (int k = 0; k < 2; ++k) {
    world.applyForce(id, Eigen::Vector3d(kHuge, 0.0, 0.0));
    world.applyTorque(id, Eigen::Vector3d(0.0, kHuge, 0.0));
  }
}

/// Ground, a resting box "victim" and, 2 m away, an independent stack of two boxes.
engine::World threeBoxes() {
  engine::World world;
  world.createBody(ground());
  world.createBody(box("victim", {0.0, 0.0, 0.1}));
  world.createBody(box("bottom", {2.0, 0.0, 0.1}));
  world.createBody(box("top", {2.0, 0.0, 0.3}));
  return world;
}

bool sameBits(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::memcmp(a.data(), b.data(), sizeof(double) * 3) == 0;
}

}  // namespace

TEST(Quarantine, OverflowingForcesIsolateTheBodyAndTheOthersAreUntouched) {
  engine::World world = threeBoxes();
  engine::World reference = threeBoxes();
  for (int n = 0; n < 10; ++n) {
    world.step();
    reference.step();
  }
  const geometry::BodyId victim = world.findBody("victim");
  const geometry::Pose before = world.pose(victim);
  overflow(world, victim);
  const engine::StepReport report = world.step();
  reference.step();
  ASSERT_EQ(report.quarantined.size(), 1u);
  EXPECT_EQ(report.quarantined[0].body, victim);
  EXPECT_EQ(report.quarantined[0].name, "victim");
  EXPECT_NE(report.quarantined[0].reason.find("non-finite velocity after the velocity prediction"),
            std::string::npos)
      << report.quarantined[0].reason;
  EXPECT_TRUE(world.quarantined(victim));
  EXPECT_TRUE(stateIsFinite(world));
  // Isolated at its last good pose, at rest, static.
  EXPECT_TRUE(sameBits(world.pose(victim).position, before.position));
  EXPECT_EQ(world.linearVelocity(victim), Eigen::Vector3d::Zero());
  EXPECT_EQ(world.state().motionTypes[victim.index], geometry::MotionType::Static);
  for (int n = 0; n < 50; ++n) {
    EXPECT_TRUE(world.step().quarantined.empty()) << "reported once, not every step";
    reference.step();
  }
  EXPECT_TRUE(stateIsFinite(world));
  // The independent stack runs bit for bit as in the world where nothing went wrong.
  for (const char* name : {"bottom", "top"}) {
    const geometry::BodyId id = world.findBody(name);
    EXPECT_TRUE(
        sameBits(world.pose(id).position, reference.pose(reference.findBody(name)).position))
        << name;
    EXPECT_TRUE(
        sameBits(world.linearVelocity(id), reference.linearVelocity(reference.findBody(name))))
        << name;
  }
  // A quarantined body leaves collision: nothing touches it any more.
  for (const geometry::ContactManifold& m : world.contacts())
    EXPECT_TRUE(m.bodyA != victim && m.bodyB != victim);
}

TEST(Quarantine, ABodyInContactIsIsolatedBeforeItsNeighbourSeesIt) {
  engine::World world = threeBoxes();
  for (int n = 0; n < 10; ++n) world.step();
  const geometry::BodyId bottom = world.findBody("bottom");
  overflow(world, bottom);  // the top box rests on it
  const engine::StepReport report = world.step();
  ASSERT_EQ(report.quarantined.size(), 1u);
  EXPECT_EQ(report.quarantined[0].name, "bottom");
  for (int n = 0; n < 100; ++n) world.step();
  EXPECT_TRUE(stateIsFinite(world));
  // The top box no longer collides with the frozen bottom box: it falls onto the ground.
  const geometry::BodyId top = world.findBody("top");
  EXPECT_NEAR(world.pose(top).position.z(), 0.1, 2e-3);
  EXPECT_LT(world.linearVelocity(top).norm(), 1e-2);
}

TEST(Quarantine, SpeedAndPositionLimitsAreEnforcedAndNamed) {
  engine::WorldSettings settings;
  settings.quarantine.maxLinearSpeed = 1e3;
  engine::World world(settings);
  world.createBody(ground());
  const geometry::BodyId fast = world.createBody(box("fast", {0.0, 0.0, 5.0}));
  const geometry::BodyId calm = world.createBody(box("calm", {3.0, 0.0, 0.1}));
  world.setVelocity(fast, Eigen::Vector3d(2e3, 0.0, 0.0), Eigen::Vector3d::Zero());
  const engine::StepReport report = world.step();
  ASSERT_EQ(report.quarantined.size(), 1u);
  EXPECT_EQ(report.quarantined[0].body, fast);
  EXPECT_NE(report.quarantined[0].reason.find("beyond the limit 1000 m/s"), std::string::npos)
      << report.quarantined[0].reason;
  EXPECT_FALSE(world.quarantined(calm));

  engine::WorldSettings far;
  far.quarantine.maxPosition = 100.0;
  engine::World drifting(far);
  const geometry::BodyId probe = drifting.createBody(box("probe", {99.0, 0.0, 0.0}));
  drifting.setGravity(Eigen::Vector3d::Zero());
  drifting.setVelocity(probe, Eigen::Vector3d(50.0, 0.0, 0.0), Eigen::Vector3d::Zero());
  bool seen = false;
  for (int n = 0; n < 10 && !seen; ++n)
    for (const engine::QuarantineEvent& e : drifting.step().quarantined)
      seen = e.reason.find("position") != std::string::npos &&
             e.reason.find("at the end of the step") != std::string::npos;
  EXPECT_TRUE(seen);
  EXPECT_LE(drifting.pose(probe).position.norm(), 100.0);  // its last good pose

  engine::WorldSettings bad;
  bad.quarantine.maxAngularSpeed = -1.0;
  EXPECT_THROW(engine::World{bad}, engine::CoulombError);
}

TEST(Quarantine, JointsOfAQuarantinedBodyBreak) {
  engine::World world;
  const geometry::BodyId a = world.createBody(box("a", {0.0, 0.0, 1.0}));
  const geometry::BodyId b = world.createBody(box("b", {0.5, 0.0, 1.0}));
  engine::JointDesc hinge;
  hinge.name = "pin";
  hinge.type = joints::JointType::Ball;
  hinge.bodyB = a;  // a hangs from the world at its centre
  hinge.frameA.anchor = Eigen::Vector3d(0.0, 0.0, 1.0);
  const geometry::JointId pin = world.createJoint(hinge);
  engine::JointDesc link = hinge;
  link.name = "link";
  link.bodyA = a;
  link.bodyB = b;
  link.frameA.anchor = Eigen::Vector3d(0.25, 0.0, 0.0);
  link.frameB.anchor = Eigen::Vector3d(-0.25, 0.0, 0.0);
  const geometry::JointId chain = world.createJoint(link);
  for (int n = 0; n < 5; ++n) world.step();
  overflow(world, a);
  ASSERT_EQ(world.step().quarantined.size(), 1u);
  EXPECT_TRUE(world.jointBroken(pin));
  EXPECT_TRUE(world.jointBroken(chain));
  for (int n = 0; n < 20; ++n) world.step();
  EXPECT_TRUE(stateIsFinite(world));
  EXPECT_LT(world.pose(b).position.z(), 0.9);  // b is free now and falls
}

TEST(Quarantine, ARunawayArticulationIsResetAndOverflowingJointForcesAreRefused) {
  engine::World world = engine::io::buildWorld(scenes::loadBuiltinScene("pendulum_reduced"));
  ASSERT_GE(world.articulations().count(), 1u);
  const geometry::ArticulationId tree{0, 0};
  for (int n = 0; n < 5; ++n) world.step();
  const auto nv = world.articulations().qd(tree).size();
  // Joint forces are refused when they would overflow the step's accumulator (ABA needs finite
  // forces); the first call is kept.
  world.applyJointForces(tree, Eigen::VectorXd::Constant(nv, kHuge));
  EXPECT_THROW(world.applyJointForces(tree, Eigen::VectorXd::Constant(nv, kHuge)),
               engine::CoulombError);
  // A joint rate beyond the limit (here 1e7 rad/s, set through the API) is reset by the guard.
  const Eigen::VectorXd q = world.articulations().q(tree);
  world.setArticulationState(tree, q, Eigen::VectorXd::Constant(nv, 1e7));
  const engine::StepReport report = world.step();
  ASSERT_EQ(report.quarantined.size(), 1u);
  EXPECT_EQ(report.quarantined[0].articulation, tree);
  EXPECT_FALSE(report.quarantined[0].body.valid());
  EXPECT_NE(report.quarantined[0].reason.find("joint"), std::string::npos);
  EXPECT_EQ(world.articulations().q(tree), q);  // back to the start of the step
  EXPECT_TRUE(world.articulations().qd(tree).isZero());
  for (int n = 0; n < 20; ++n) EXPECT_TRUE(world.step().quarantined.empty());
  EXPECT_TRUE(stateIsFinite(world));
  EXPECT_TRUE(world.articulations().q(tree).allFinite());
}
