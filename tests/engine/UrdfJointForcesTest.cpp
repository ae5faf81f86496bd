// URDF joint friction and constant joint torques on a reduced-coordinate tree (docs/urdf.md,
// "Joint friction", "Joint torques in a scene"). The fixture tests/data/urdf/mechanisms/
// arm_friction.urdf is a 1 kg bob at l = 0.5 m from a continuous joint about y, friction
// f = 2 N m, inertia about the pivot I = 0.251 kg m^2; at angle q the gravity torque is
// m g l cos q (4.905 N m horizontal). Checks:
//  - below breakaway (|load| < f) the joint stays still: the friction row holds it;
//  - above it the joint accelerates with (load - f) / I (analytic, to 1e-9 relative after one step;
//    over 0.2 s the engine matches the semi-implicit Euler recurrence of I qdd = load - f);
//  - a constant scene torque by joint name adds to the load: qdd = (tau + m g l - f) / I, also
//    with friction turned off (zero gravity: qdd = tau / I);
//  - bad entries name the joint.
#include <coulomb/engine/CoulombError.hpp>
#include <coulomb/engine/World.hpp>
#include <coulomb/io/SceneLoader.hpp>
#include <coulomb/urdf/UrdfLoader.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <string>

namespace {

using namespace coulomb;

const std::filesystem::path kData = std::filesystem::path(COULOMB_TEST_DATA_DIR) / "urdf";
constexpr double kMass = 1.0, kLength = 0.5, kInertia = 0.001 + kMass * kLength * kLength;
constexpr double kFriction = 2.0, kG = 9.81, kH = 0.005;

/// The arm in a scene (no floor: the arm has no shapes), with `extra` keys in its urdf entry.
engine::World armWorld(const std::string& extra, const std::string& gravity = "[0, 0, -9.81]") {
  const std::string text = R"({"time_step": 0.005, "gravity": )" + gravity +
                           R"(, "urdf": [{"file": "mechanisms/arm_friction.urdf", "name": "arm")" +
                           extra + "}]}";
  return engine::io::buildWorld(engine::io::parseScene(text, "arm.json", kData));
}

/// Joint rate after one step from rest at q = 0, and the angle after `steps` steps.
struct Outcome {
  double rateAfterOneStep = 0.0;
  double angle = 0.0;
};
Outcome run(engine::World world, int steps) {
  const geometry::ArticulationId id{0, 0};
  Outcome r;
  for (int k = 0; k < steps; ++k) {
    world.step(kH);
    if (k == 0) r.rateAfterOneStep = world.articulations().qd(id)[0];
  }
  r.angle = world.articulations().q(id)[0];
  EXPECT_TRUE(std::isfinite(r.angle));
  return r;
}

/// Semi-implicit Euler of I qdd = tau + m g l cos q - f sign (sliding, never sticking again).
double recurrence(double tau, int steps) {
  double q = 0.0, qd = 0.0;
  for (int k = 0; k < steps; ++k) {
    qd += kH * (tau + kMass * kG * kLength * std::cos(q) - kFriction) / kInertia;
    q += kH * qd;
  }
  return q;
}

TEST(UrdfJointFriction, LoaderKeepsFrictionAndDescCarriesIt) {
  const auto model = engine::io::loadUrdfFile(kData / "mechanisms/arm_friction.urdf");
  ASSERT_EQ(model.bodies.size(), 2u);
  EXPECT_EQ(model.bodies[1].jointFriction, kFriction);
  const engine::ArticulationDesc desc = engine::io::toArticulationDesc(model, "arm");
  EXPECT_EQ(desc.links[1].jointFriction, kFriction);
}

TEST(UrdfJointFriction, HoldsBelowBreakawayAndSlidesAboveIt) {
  // Held: the gravity torque 4.905 N m plus a scene torque of -3.5 N m leaves 1.405 N m < f.
  const Outcome held = run(armWorld(R"(, "torques": {"pivot": -3.5})"), 400);  // 2 s
  std::cout << "friction 2 N m, load 1.405 N m, 2 s: angle " << held.angle << " rad\n";
  EXPECT_LT(std::abs(held.angle), 1e-6);
  // Just below breakaway from the other side: load -1.9 N m (torque -6.805).
  const Outcome heldOther = run(armWorld(R"(, "torques": {"pivot": -6.805})"), 400);
  std::cout << "friction 2 N m, load -1.9 N m, 2 s: angle " << heldOther.angle << " rad\n";
  EXPECT_LT(std::abs(heldOther.angle), 1e-6);

  // Sliding: gravity alone, 4.905 N m > f: qdd = (4.905 - 2) / 0.251.
  const Outcome sliding = run(armWorld(""), 40);  // 0.2 s
  const double expected = (kMass * kG * kLength - kFriction) / kInertia;
  std::cout << "friction 2 N m, gravity 4.905 N m: qdd " << sliding.rateAfterOneStep / kH
            << " rad/s^2 (analytic " << expected << ", rel. error "
            << std::abs(sliding.rateAfterOneStep / kH - expected) / expected
            << "); angle after 0.2 s " << sliding.angle << " (recurrence " << recurrence(0.0, 40)
            << ")\n";
  EXPECT_NEAR(sliding.rateAfterOneStep / kH, expected, 1e-9 * expected);
  EXPECT_NEAR(sliding.angle, recurrence(0.0, 40), 1e-9);
  // Without friction the arm would fall faster: the friction is really acting.
  EXPECT_LT(sliding.angle, 0.5 * kH * kH * 40 * 40 * kMass * kG * kLength / kInertia * 0.8);
}

TEST(UrdfJointTorque, ConstantTorqueGivesTheAnalyticAcceleration) {
  // With gravity and friction: qdd = (3 + 4.905 - 2) / I.
  const Outcome pushed = run(armWorld(R"(, "torques": {"pivot": 3.0})"), 40);
  const double expected = (3.0 + kMass * kG * kLength - kFriction) / kInertia;
  std::cout << "torque 3 N m + gravity - friction: qdd " << pushed.rateAfterOneStep / kH
            << " (analytic " << expected << ", rel. error "
            << std::abs(pushed.rateAfterOneStep / kH - expected) / expected << ")\n";
  EXPECT_NEAR(pushed.rateAfterOneStep / kH, expected, 1e-9 * expected);
  EXPECT_NEAR(pushed.angle, recurrence(3.0, 40), 1e-9);
  // Zero gravity, torque -5 N m beyond the friction: qdd = (-5 + 2) / I, constant every step.
  const Outcome weightless = run(armWorld(R"(, "torques": {"pivot": -5.0})", "[0, 0, 0]"), 40);
  const double a = (-5.0 + kFriction) / kInertia;
  std::cout << "torque -5 N m, no gravity: qdd " << weightless.rateAfterOneStep / kH
            << " (analytic " << a << "), angle after 0.2 s " << weightless.angle
            << " (semi-implicit Euler a h^2 n (n + 1) / 2: " << a * kH * kH * 40 * 41 / 2 << ")\n";
  EXPECT_NEAR(weightless.rateAfterOneStep / kH, a, 1e-9 * std::abs(a));
  // Semi-implicit Euler: q_n = a h^2 n (n + 1) / 2.
  EXPECT_NEAR(weightless.angle, a * kH * kH * 40 * 41 / 2, 1e-9);
}

TEST(UrdfJointTorque, MisspeltJointIsNamed) {
  try {
    (void)armWorld(R"(, "torques": {"pivto": 1.0})");
    FAIL() << "expected an error";
  } catch (const engine::CoulombError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("torques"), std::string::npos) << message;
    EXPECT_NE(message.find("pivto"), std::string::npos) << message;
    EXPECT_NE(message.find("did you mean 'pivot'"), std::string::npos) << message;
  }
}

TEST(UrdfJointFriction, NegativeFrictionIsRefused) {
  engine::ArticulationDesc desc = engine::io::toArticulationDesc(
      engine::io::loadUrdfFile(kData / "mechanisms/arm_friction.urdf"), "arm");
  desc.links[1].jointFriction = -1.0;
  engine::World world;
  EXPECT_THROW(world.createArticulation(desc), engine::CoulombError);
  EXPECT_EQ(world.articulations().count(), 0u);
}

}  // namespace
