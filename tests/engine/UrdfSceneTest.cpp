// URDF robots in scenes (io/UrdfScene): the JSON `urdf` section, tree joint motors
// (bounded rows in joint space) and mimic couplings (equality rows in joint space).
//  - kuka_iiwa, fixed base, held by position motors under gravity: joints stay within 1e-3 rad;
//  - anymal_c, floating base, standing on a floor with its 12 joints held: the base stays within
//    2 cm of its settled height and the joints within 0.05 rad;
//  - a velocity motor reaches its target and a weak one saturates at its effort bound;
//  - a mimic coupling keeps q_follower = m q_leader + offset; pr2's mimics become couplings;
//  - bad entries name the scene, the JSON path and the joint.
#include <coulomb/engine/CoulombError.hpp>
#include <coulomb/engine/World.hpp>
#include <coulomb/io/SceneLoader.hpp>
#include <coulomb/io/UrdfScene.hpp>

#include <gtest/gtest.h>

#include <iostream>
#include <string>

namespace {

using namespace coulomb;
using engine::io::parseScene;

const std::filesystem::path kCorpus = std::filesystem::path(COULOMB_TEST_DATA_DIR) / "urdf";

std::string withFloor(const std::string& urdfSection) {
  return R"({"time_step": 0.005, "bodies": [{"name": "floor", "type": "static",
             "shapes": [{"type": "plane"}]}], "urdf": [)" +
         urdfSection + "]}";
}

double maxJointDrift(const Eigen::VectorXd& q, const Eigen::VectorXd& q0, int first) {
  return (q.tail(q.size() - first) - q0.tail(q0.size() - first)).cwiseAbs().maxCoeff();
}

TEST(UrdfScene, KukaHeldByMotorsStaysPut) {
  const auto scene = parseScene(withFloor(R"({"file": "kuka_iiwa/model.urdf", "name": "kuka",
      "q": {"lbr_iiwa_joint_2": 0.6, "lbr_iiwa_joint_4": -1.2}, "hold": true})"),
                                "kuka.json", kCorpus);
  ASSERT_EQ(scene.articulations.size(), 1u);
  EXPECT_EQ(scene.articulations[0].motors.size(), 7u);
  engine::World world = engine::io::buildWorld(scene);
  const geometry::ArticulationId id{0, 0};
  const Eigen::VectorXd q0 = world.articulations().q(id);
  EXPECT_NEAR(q0[1], 0.6, 1e-15);
  for (int step = 0; step < 400; ++step) world.step(0.005);  // 2 s
  const Eigen::VectorXd& q = world.articulations().q(id);
  ASSERT_TRUE(q.allFinite());
  const double drift = maxJointDrift(q, q0, 0);
  std::cout << "kuka held by motors, 2 s: max joint drift " << drift << " rad\n";
  EXPECT_LT(drift, 1e-3);
  // Without motors the same arm falls: the test can fail.
  auto loose = parseScene(withFloor(R"({"file": "kuka_iiwa/model.urdf",
      "q": {"lbr_iiwa_joint_2": 0.6, "lbr_iiwa_joint_4": -1.2}})"),
                          "kuka.json", kCorpus);
  engine::World falling = engine::io::buildWorld(loose);
  for (int step = 0; step < 100; ++step) falling.step(0.005);
  EXPECT_GT(maxJointDrift(falling.articulations().q(id), q0, 0), 0.05);
}

TEST(UrdfScene, AnymalStandsOnTheFloorWithHeldJoints) {
  const auto scene = parseScene(withFloor(R"({"file": "anymal_c/anymal.urdf", "name": "anymal",
      "base": "floating", "on_floor": 0.0, "hold": true,
      "q": {"LF_HFE": 0.4, "LF_KFE": -0.8, "RF_HFE": 0.4, "RF_KFE": -0.8,
            "LH_HFE": -0.4, "LH_KFE": 0.8, "RH_HFE": -0.4, "RH_KFE": 0.8}})"),
                                "anymal.json", kCorpus);
  engine::World world = engine::io::buildWorld(scene);
  const geometry::ArticulationId id{0, 0};
  const Eigen::VectorXd q0 = world.articulations().q(id);
  const double startHeight = world.articulations().linkPose(id, 0).position.z();
  for (int step = 0; step < 100; ++step) world.step(0.005);  // settle 0.5 s
  const Eigen::VectorXd settled = world.articulations().q(id);
  const double settledHeight = world.articulations().linkPose(id, 0).position.z();
  for (int step = 0; step < 300; ++step) world.step(0.005);  // 1.5 s more
  const Eigen::VectorXd& q = world.articulations().q(id);
  ASSERT_TRUE(q.allFinite());
  const double height = world.articulations().linkPose(id, 0).position.z();
  const double heightDrift = std::abs(height - settledHeight);
  const double jointDrift = maxJointDrift(q, settled, 7);
  std::cout << "anymal standing: base height " << height << " m (placed " << startHeight
            << ", settled " << settledHeight << "), height drift over 1.5 s " << heightDrift
            << " m, joint drift " << jointDrift << " rad (from the initial pose "
            << maxJointDrift(q, q0, 7) << ")\n";
  EXPECT_GT(height, 0.3);  // standing, not collapsed
  EXPECT_LT(heightDrift, 0.02);
  EXPECT_LT(jointDrift, 0.05);
}

engine::ArticulationDesc twoHinges() {
  engine::ArticulationDesc desc;
  desc.name = "pair";
  for (int i = 0; i < 2; ++i) {
    engine::ArticulationLinkDesc link;
    link.name = "link" + std::to_string(i);
    link.joint = joints::tree::TreeJoint::revolute("hinge" + std::to_string(i),
                                                   geometry::Pose::translation({0.0, 2.0 * i, 0.0}),
                                                   Eigen::Vector3d::UnitY());
    link.inertia = geometry::SpatialInertia{1.0, {0.5, 0, 0}, 0.1 * Eigen::Matrix3d::Identity()};
    desc.links.push_back(link);
  }
  return desc;
}

TEST(UrdfScene, VelocityMotorReachesItsTargetAndSaturatesAtItsEffort) {
  engine::WorldSettings settings;
  settings.gravity.setZero();
  engine::World world(settings);
  engine::ArticulationDesc desc = twoHinges();
  desc.motors.push_back({0, engine::JointMotorMode::Velocity, 2.0, 500.0});
  desc.motors.push_back({1, engine::JointMotorMode::Velocity, 2.0, 0.1});  // weak
  const auto id = world.createArticulation(desc);
  world.step(0.01);
  EXPECT_NEAR(world.articulations().qd(id)[0], 2.0, 1e-6);
  // Link 1: I about the hinge = 0.1 + 1 * 0.5^2 = 0.35; 0.1 N m for 0.01 s gives 0.1 * 0.01 / 0.35.
  EXPECT_NEAR(world.articulations().qd(id)[1], 0.1 * 0.01 / 0.35, 1e-6);
  world.setJointMotorTarget(id, 0, -1.0);
  world.step(0.01);
  EXPECT_NEAR(world.articulations().qd(id)[0], -1.0, 1e-6);
  EXPECT_THROW(world.setJointMotorTarget(id, 5, 0.0), engine::CoulombError);
}

TEST(UrdfScene, MimicCouplingKeepsTheFollowerOnItsLeader) {
  engine::World world;  // gravity pulls both links down at different rates without the coupling
  engine::ArticulationDesc desc = twoHinges();
  desc.links[1].inertia =
      geometry::SpatialInertia{3.0, {0.2, 0, 0}, 0.05 * Eigen::Matrix3d::Identity()};
  desc.couplings.push_back({1, 0, -0.5, 0.1});  // q1 = -0.5 q0 + 0.1
  desc.q = Eigen::Vector2d(0.0, 0.1);
  const auto id = world.createArticulation(desc);
  double worst = 0.0;
  for (int step = 0; step < 200; ++step) {
    world.step(0.01);
    const Eigen::VectorXd& q = world.articulations().q(id);
    worst = std::max(worst, std::abs(q[1] + 0.5 * q[0] - 0.1));
  }
  const Eigen::VectorXd& q = world.articulations().q(id);
  std::cout << "mimic coupling: worst |q1 - (-0.5 q0 + 0.1)| over 2 s: " << worst << " (q0 " << q[0]
            << ")\n";
  EXPECT_GT(std::abs(q[0]), 0.1);  // it moved
  EXPECT_LT(worst, 1e-3);
  // Bad couplings are refused with the articulation named.
  engine::ArticulationDesc bad = twoHinges();
  bad.couplings.push_back({1, 1, 1.0, 0.0});
  EXPECT_THROW(world.createArticulation(bad), engine::CoulombError);
}

TEST(UrdfScene, Pr2MimicJointsBecomeCouplings) {
  const auto scene =
      parseScene(withFloor(R"({"file": "pr2/pr2.urdf", "mimic": true})"), "pr2.json", kCorpus);
  ASSERT_EQ(scene.articulations.size(), 1u);
  EXPECT_EQ(scene.articulations[0].couplings.size(), 10u);
}

std::string errorOf(const std::string& section) {
  try {
    (void)parseScene(withFloor(section), "robots.json", kCorpus);
  } catch (const engine::CoulombError& e) {
    return e.what();
  }
  return "";
}

TEST(UrdfScene, BadEntriesNameTheSceneThePathAndTheJoint) {
  const std::string unknownJoint =
      errorOf(R"({"file": "kuka_iiwa/model.urdf", "q": {"lbr_iiwa_joint_9": 1}})");
  EXPECT_NE(unknownJoint.find("robots.json: urdf[0]"), std::string::npos) << unknownJoint;
  EXPECT_NE(unknownJoint.find("lbr_iiwa_joint_9"), std::string::npos) << unknownJoint;
  EXPECT_NE(unknownJoint.find("did you mean"), std::string::npos) << unknownJoint;
  const std::string missing = errorOf(R"({"file": "nowhere/robot.urdf"})");
  EXPECT_NE(missing.find("urdf[0]"), std::string::npos) << missing;
  EXPECT_NE(missing.find("not found"), std::string::npos) << missing;
  const std::string badBase = errorOf(R"({"file": "kuka_iiwa/model.urdf", "base": "free"})");
  EXPECT_NE(badBase.find("urdf[0].base"), std::string::npos) << badBase;
  const std::string refused = errorOf(R"({"file": "acrobot/Acrobot.urdf"})");
  EXPECT_NE(refused.find("Acrobot.urdf:62"), std::string::npos) << refused;
  const std::string typo = errorOf(R"({"file": "kuka_iiwa/model.urdf", "hodl": true})");
  EXPECT_NE(typo.find("hold"), std::string::npos) << typo;
}

}  // namespace
