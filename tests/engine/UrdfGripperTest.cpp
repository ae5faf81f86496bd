// A gripper holding a box (docs/urdf.md, "A gripper holding a box"): tests/data/urdf/mechanisms/
// gripper.urdf, two prismatic fingers driven by position motors whose effort is bounded by the
// URDF's <limit effort> F = 20 N, squeeze a 0.5 kg box (0.1 m cube) against gravity. The fingers'
// friction comes from the scene material "rubber" (their visual material), the box uses it too,
// so the contact friction is mu (geometric mean of equal values). Coulomb: the box is held iff
// the friction available on the two faces, 2 mu F, exceeds its weight m g = 4.905 N:
//  - mu = 0.5: 2 mu F = 20 N > 4.905 N: the box slips less than 2 mm in 2 s;
//  - mu = 0.1: 2 mu F = 4 N < 4.905 N: it slides down (a > 0; the test can fail);
//  - opening the fingers (targets 0) releases the box: it falls freely.
#include <coulomb/engine/World.hpp>
#include <coulomb/io/SceneLoader.hpp>

#include <gtest/gtest.h>

#include <iostream>
#include <string>

namespace {

using namespace coulomb;

const std::filesystem::path kData = std::filesystem::path(COULOMB_TEST_DATA_DIR) / "urdf";
constexpr double kH = 0.005;

engine::World gripperWorld(double mu) {
  // Palm at z = 0.5; the fingers span z 0.34..0.46; the box (centre 0.4) touches them at
  // q = 0.09 - 0.05 = 0.04; they start 0.5 mm open and their targets are 2 cm inside the box, so
  // the position motors saturate at their effort bound and squeeze with 20 N each.
  const std::string text = R"({"time_step": 0.005, "gravity": [0, 0, -9.81],
    "materials": {"rubber": {"friction": )" +
                           std::to_string(mu) + R"(}},
    "bodies": [{"name": "box", "position": [0, 0, 0.4], "density": 500,
                "shapes": [{"type": "box", "half_extents": [0.05, 0.05, 0.05],
                            "material": "rubber"}]}],
    "urdf": [{"file": "mechanisms/gripper.urdf", "name": "gripper", "position": [0, 0, 0.5],
              "q": {"left_finger_joint": 0.0395, "right_finger_joint": 0.0395},
              "motors": {"left_finger_joint": 0.06, "right_finger_joint": 0.06}}]})";
  return engine::io::buildWorld(engine::io::parseScene(text, "gripper.json", kData));
}

double boxZ(const engine::World& world) {
  return world.pose(world.findBody("box")).position.z();
}

TEST(UrdfGripper, HoldsTheBoxWithEnoughFrictionAndReleasesIt) {
  engine::World world = gripperWorld(0.5);
  const geometry::ArticulationId gripper{0, 0};
  EXPECT_NEAR(world.massProperties(world.findBody("box")).mass, 0.5, 1e-12);
  const double z0 = boxZ(world);
  double lowest = z0;
  for (int k = 0; k < 400; ++k) {  // 2 s
    world.step(kH);
    lowest = std::min(lowest, boxZ(world));
  }
  const double slip = z0 - lowest;
  const Eigen::VectorXd& q = world.articulations().q(gripper);
  std::cout << "mu 0.5 (2 mu F = 20 N vs weight 4.905 N): box slip over 2 s " << slip
            << " m; finger q " << q.transpose() << " m\n";
  EXPECT_LT(slip, 2e-3);
  EXPECT_GT(q[0], 0.0395);  // closed onto the box (penetration aside), not through it
  EXPECT_LT(q[0], 0.042);
  EXPECT_LT(world.linearVelocity(world.findBody("box")).norm(), 1e-3);

  // Open: both targets back to 0. The box is free and falls (0.2 s of free fall: ~0.2 m).
  world.setJointMotorTarget(gripper, 0, 0.0);
  world.setJointMotorTarget(gripper, 1, 0.0);
  const double zOpen = boxZ(world);
  for (int k = 0; k < 40; ++k) world.step(kH);
  const double fall = zOpen - boxZ(world);
  std::cout << "fingers opened: box fell " << fall << " m in 0.2 s (free fall 0.196 m); finger q "
            << world.articulations().q(gripper).transpose() << "\n";
  EXPECT_GT(fall, 0.1);
}

TEST(UrdfGripper, SlipsWhenFrictionCannotCarryTheWeight) {
  engine::World world = gripperWorld(0.1);
  const double z0 = boxZ(world);
  for (int k = 0; k < 20; ++k) world.step(kH);  // 0.1 s: the faces still overlap
  const double slip = z0 - boxZ(world);
  // Sliding friction 2 mu F = 4 N against m g = 4.905 N: a = 0.905 / 0.5 = 1.81 m/s^2; semi-
  // implicit Euler from rest covers a h^2 n (n + 1) / 2 = 9.5 mm in 20 steps.
  const double expected = (0.5 * 9.81 - 2.0 * 0.1 * 20.0) / 0.5 * kH * kH * 20 * 21 / 2;
  const double speed = -world.linearVelocity(world.findBody("box")).z();
  std::cout << "mu 0.1 (2 mu F = 4 N < 4.905 N): box slid " << slip << " m in 0.1 s (Coulomb "
            << expected << " m), sliding deceleration of friction " << 9.81 - speed / 0.1
            << " m/s^2 (2 mu F / m = 8 m/s^2)\n";
  EXPECT_NEAR(slip, expected, 0.1 * expected);
}

}  // namespace
