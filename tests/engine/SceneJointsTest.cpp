// The "joints" section of a JSON scene (docs/scene-format.md "Joints"): both ways of giving the
// frames produce closed joints in the World, every option reaches the JointDef, and every error
// names the source, the JSON path and the problem.
#include <gtest/gtest.h>
#include <coulomb/engine/CoulombError.hpp>
#include <coulomb/io/SceneLoader.hpp>
#include "SceneErrorTestHelpers.hpp"

#include <Eigen/Geometry>

#include <cmath>
#include <numbers>
#include <string>

using namespace coulomb;
using engine::io::parseScene;

namespace {

// Two boxes: "arm" at (1, 0, 0) turned 90 deg about z, "hand" at (2, 0, 0), both 1 kg.
std::string twoBodies(const std::string& joints, const std::string& extra = "") {
  const std::string shape = R"("shapes": [{"type": "box", "half_extents": [0.1, 0.1, 0.1]}])";
  return R"({"gravity": [0, 0, 0], )" + extra + R"("bodies": [
    {"name": "arm", "position": [1, 0, 0], "orientation": {"axis": [0, 0, 1], "angle": 1.5707963267948966}, )" +
         shape + R"(},
    {"name": "hand", "position": [2, 0, 0], )" +
         shape + R"(}],
  "joints": [)" +
         joints + "]}";
}

std::string errorOf(const std::string& text, bool build = false) {
  return test::sceneErrorOf(text, build);
}

struct WorldFrame {
  Eigen::Vector3d anchor, axis, normal;
};

WorldFrame worldFrame(const engine::World& world, geometry::BodyId body,
                      const joints::JointFrame& f) {
  if (!body.valid()) return {f.anchor, f.axis, f.normal};
  const geometry::Pose& pose = world.state().poses[body.index];
  return {pose.apply(f.anchor), pose.rotation * f.axis, pose.rotation * f.normal};
}

}  // namespace

TEST(SceneJoints, WorldCoordinateFramesAreClosedAndAlignedInTheWorld) {
  const engine::io::Scene scene =
      parseScene(twoBodies(R"({"name": "wrist", "type": "hinge", "body_a": "arm", "body_b": "hand",
                    "anchor": [1.5, 0, 0], "axis": [0, 2, 0], "normal": [0, 0, 1]},
                   {"type": "ball", "body_b": "arm", "anchor": [0.5, 0, 0]})"),
                 "test.json");
  ASSERT_EQ(scene.joints.size(), 2U);
  EXPECT_EQ(scene.joints[0].bodyA, 0);
  EXPECT_EQ(scene.joints[0].bodyB, 1);
  EXPECT_EQ(scene.joints[1].bodyA, -1);  // absent = the world
  // In the arm's frame (turned +90 deg about z) the world point (1.5, 0, 0) is (0, -0.5, 0).
  EXPECT_TRUE(scene.joints[0].def.frameA.anchor.isApprox(Eigen::Vector3d(0, -0.5, 0), 1e-12));
  EXPECT_TRUE(scene.joints[0].def.frameA.axis.isApprox(Eigen::Vector3d(1, 0, 0), 1e-12));

  const engine::World world = engine::io::buildWorld(scene);
  ASSERT_EQ(world.jointCount(), 2U);
  const geometry::BodyId arm = world.findBody("arm"), hand = world.findBody("hand");
  const geometry::JointId wrist{0, 0};  // joint i of a built scene has slot i (SceneLoader.hpp)
  const joints::JointDef& def = world.joint(wrist);
  ASSERT_EQ(def.name, "wrist");
  const WorldFrame a = worldFrame(world, arm, def.frameA), b = worldFrame(world, hand, def.frameB);
  EXPECT_LT((a.anchor - b.anchor).norm(), 1e-12);
  EXPECT_LT((a.anchor - Eigen::Vector3d(1.5, 0, 0)).norm(), 1e-12);
  EXPECT_LT((a.axis - Eigen::Vector3d::UnitY()).norm(), 1e-12);  // normalized from [0, 2, 0]
  EXPECT_LT((b.normal - Eigen::Vector3d::UnitZ()).norm(), 1e-12);
}

TEST(SceneJoints, PerBodyFramesAreTakenInTheBodiesFrames) {
  const engine::io::Scene scene =
      parseScene(twoBodies(R"({"type": "prismatic", "body_a": "arm", "body_b": "hand",
                    "frame_a": {"anchor": [0, -1, 0], "axis": [1, 0, 0]},
                    "frame_b": {"anchor": [0, 0, 0], "axis": [0, -1, 0]}})"),
                 "test.json");
  const joints::JointDef& def = scene.joints.at(0).def;
  EXPECT_TRUE(def.frameA.anchor.isApprox(Eigen::Vector3d(0, -1, 0)));
  EXPECT_TRUE(def.frameB.axis.isApprox(Eigen::Vector3d(0, -1, 0)));
  EXPECT_NEAR(def.frameA.normal.dot(def.frameA.axis), 0.0, 1e-15);  // a default normal
  EXPECT_NEAR(def.frameA.normal.norm(), 1.0, 1e-15);
  EXPECT_EQ(engine::io::buildWorld(scene).jointCount(), 1U);
}

TEST(SceneJoints, LimitMotorFrictionBreakAndStabilizationReachTheJoint) {
  const engine::io::Scene scene = parseScene(
      twoBodies(R"({"type": "hinge", "body_a": "arm", "body_b": "hand", "anchor": [1.5, 0, 0],
                    "axis": [0, 1, 0], "limit": {"lower": -0.5, "upper": 1, "restitution": 0.3},
                    "motor": {"target_velocity": 2, "max_torque": 4}, "break_force": 100,
                    "break_torque": 20, "stabilization": {"method": "baumgarte", "beta": 0.4}},
                   {"type": "prismatic", "body_a": "arm", "body_b": "hand", "anchor": [1.5, 0, 0],
                    "axis": [1, 0, 0], "friction": 3, "stabilization": "none"})",
                R"("joint_stabilization": {"iterations": 7, "tolerance": 1e-8}, )"),
      "test.json");
  EXPECT_EQ(scene.settings.jointStabilization.predictedState.iterations, 7);
  EXPECT_DOUBLE_EQ(scene.settings.jointStabilization.predictedState.tolerance, 1e-8);
  const joints::JointDef& hinge = scene.joints.at(0).def;
  EXPECT_TRUE(hinge.limit.enabled);
  EXPECT_DOUBLE_EQ(hinge.limit.lower, -0.5);
  EXPECT_DOUBLE_EQ(hinge.limit.upper, 1.0);
  EXPECT_DOUBLE_EQ(hinge.limit.restitution, 0.3);
  EXPECT_TRUE(hinge.motor.enabled);
  EXPECT_DOUBLE_EQ(hinge.motor.targetVelocity, 2.0);
  EXPECT_DOUBLE_EQ(hinge.motor.maxForce, 4.0);
  EXPECT_DOUBLE_EQ(hinge.breakForce, 100.0);
  EXPECT_DOUBLE_EQ(hinge.breakTorque, 20.0);
  ASSERT_TRUE(hinge.stabilization.has_value());
  EXPECT_EQ(hinge.stabilization->method, joints::StabilizationMethod::Baumgarte);
  EXPECT_DOUBLE_EQ(hinge.stabilization->baumgarte.beta, 0.4);
  EXPECT_EQ(hinge.stabilization->predictedState.iterations, 7);  // from the world's policy
  const joints::JointDef& slider = scene.joints.at(1).def;
  EXPECT_DOUBLE_EQ(slider.friction, 3.0);
  EXPECT_FALSE(slider.motor.enabled);
  EXPECT_TRUE(std::isinf(slider.breakForce));  // default: unbreakable
  EXPECT_EQ(slider.stabilization->method, joints::StabilizationMethod::None);
  EXPECT_EQ(engine::io::buildWorld(scene).jointCount(), 2U);
}

TEST(SceneJoints, ErrorsNameTheFileThePathAndTheProblem) {
  const std::string hand = R"("body_a": "arm", "body_b": "hand", "anchor": [1.5, 0, 0])";
  EXPECT_CONTAINS(errorOf(twoBodies(R"({"type": "hinje", "axis": [0, 1, 0], )" + hand + "}")),
                  "test.json: joints[0].type: unknown joint type 'hinje'; did you mean 'hinge'?");
  EXPECT_CONTAINS(
      errorOf(
          twoBodies(R"({"type": "ball", "body_a": "arn", "body_b": "hand", "anchor": [0, 0, 0]})")),
      "test.json: joints[0].body_a: unknown body 'arn'; did you mean 'arm'?");
  EXPECT_CONTAINS(errorOf(twoBodies(R"({"type": "ball", "anchor": [0, 0, 0]})")),
                  "joints[0]: at least one of body_a, body_b must be a body");
  EXPECT_CONTAINS(errorOf(twoBodies(R"({"type": "ball", "body_a": "arm", "body_b": "arm",
                                        "anchor": [0, 0, 0]})")),
                  "joints[0].body_b: a joint needs two different bodies");
  EXPECT_CONTAINS(errorOf(twoBodies(R"({"type": "hinge", )" + hand + "}")),
                  "joints[0]: \"axis\" is required for a hinge");
  EXPECT_CONTAINS(
      errorOf(twoBodies(R"({"type": "ball", )" + hand + R"(, "frame_a": {"anchor": [0, 0, 0]}})")),
      "joints[0]: give the frame either in world coordinates");
  EXPECT_CONTAINS(errorOf(twoBodies(R"({"type": "ball", "body_a": "arm", "body_b": "hand",
                                        "frame_a": {"anchor": [0, 0, 0]}})")),
                  "joints[0]: \"frame_b\" is missing");
  EXPECT_CONTAINS(
      errorOf(
          twoBodies(R"({"type": "hinge", "axis": [0, 1, 0], "normal": [0, 1, 1], )" + hand + "}")),
      "joints[0].normal: must be perpendicular to \"axis\"");
  EXPECT_CONTAINS(
      errorOf(twoBodies(R"({"type": "ball", "limit": {"lower": 0, "upper": 1}, )" + hand + "}")),
      "joints[0].limit: only hinge and prismatic joints have a limit");
  EXPECT_CONTAINS(errorOf(twoBodies(R"({"type": "hinge", "axis": [0, 1, 0], )" + hand +
                                    R"(, "limit": {"lower": 1, "upper": 0}})")),
                  "joints[0].limit.upper: must be >= \"lower\"");
  EXPECT_CONTAINS(errorOf(twoBodies(R"({"type": "hinge", "axis": [0, 1, 0], )" + hand +
                                    R"(, "motor": {"target_velocity": 1}})")),
                  "joints[0].motor: give one of \"max_force\"");
  EXPECT_CONTAINS(
      errorOf(twoBodies(R"({"type": "ball", "stabilization": "baumgarten", )" + hand + "}")),
      "joints[0].stabilization: unknown stabilization 'baumgarten'; did you mean "
      "'baumgarte'?");
  EXPECT_CONTAINS(errorOf(twoBodies(R"({"type": "ball", "break_force": 0, )" + hand + "}")),
                  "joints[0].break_force: must be > 0");
  EXPECT_CONTAINS(errorOf(twoBodies(R"({"type": "ball", "ancor": [0, 0, 0], )" + hand + "}")),
                  "joints[0].ancor: unknown key 'ancor'; did you mean 'anchor'?");
  EXPECT_CONTAINS(errorOf(twoBodies("", R"("joint_stabilization": {"beta": 2}, )")),
                  "joint_stabilization.beta: must be in [0, 1]");
  // Caught by the World (JointDef validation), anchored at the joint's JSON path.
  EXPECT_CONTAINS(errorOf(twoBodies(R"({"type": "hinge", "axis": [0, 1, 0], "friction": 1,
                                        "motor": {"max_torque": 1}, )" +
                                    hand + "}"),
                          true),
                  "test.json: joints[0]: joint '' (hinge): has both a motor and friction");
}
