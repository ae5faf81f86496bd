// URDF robots in maximal coordinates (urdf/UrdfMaximal, docs/urdf.md "Maximal
// coordinates"): the same model as free bodies + hinge joints and as a reduced tree.
//  - from rest at a bent configuration, one small step gives the joint accelerations of the tree
//    (ABA, Featherstone 2008 Table 7.1), measured as the hinges' relative angular rates / h;
//  - over 1 s the joint angles follow the tree's trajectory and the joints stay closed (anchor
//  gap);
//  - a JSON scene entry with "coordinates": "maximal" makes bodies and joints; errors name why.
#include <coulomb/engine/CoulombError.hpp>
#include <coulomb/engine/World.hpp>
#include <coulomb/io/SceneLoader.hpp>
#include <coulomb/io/UrdfScene.hpp>
#include <coulomb/joints/tree/TreeDynamics.hpp>
#include <coulomb/urdf/UrdfMaximal.hpp>

#include <gtest/gtest.h>
#include <Eigen/Geometry>

#include <cmath>
#include <iostream>
#include <string>

namespace {

using namespace coulomb;
using engine::io::UrdfModel;

const std::filesystem::path kCorpus = std::filesystem::path(COULOMB_TEST_DATA_DIR) / "urdf";

UrdfModel load(const std::string& file) {
  engine::io::UrdfOptions options;
  options.loadCollisionMeshes = false;
  options.jointDamping = false;  // maximal joints carry no damping: compare like with like
  return engine::io::loadUrdfFile(kCorpus / file, options);
}

/// A bent configuration: joint i at 0.3 + 0.25 i (alternating sign), within the limits.
Eigen::VectorXd bent(const joints::tree::Articulation& tree) {
  Eigen::VectorXd q = tree.neutralConfiguration();
  for (Eigen::Index i = 0; i < q.size(); ++i) q[i] = (i % 2 == 0 ? 1.0 : -1.0) * (0.3 + 0.1 * i);
  return q;
}

/// World pose of a joint frame (JointDef frames are in the bodies' COM frames as stored).
geometry::Pose endPose(const engine::World& world, geometry::BodyId body) {
  return body.valid() ? world.pose(body) : geometry::Pose::identity();
}

/// Hinge angle: of normal_B about axis_A (JointDef.hpp).
double hingeAngle(const engine::World& world, const joints::JointDef& def) {
  const geometry::Pose a = endPose(world, def.bodyA), b = endPose(world, def.bodyB);
  const Eigen::Vector3d axis = a.rotation * def.frameA.axis;
  const Eigen::Vector3d nA = a.rotation * def.frameA.normal, nB = b.rotation * def.frameB.normal;
  return std::atan2(axis.dot(nA.cross(nB)), nA.dot(nB));
}

double hingeRate(const engine::World& world, const joints::JointDef& def) {
  const Eigen::Vector3d axis = endPose(world, def.bodyA).rotation * def.frameA.axis;
  const Eigen::Vector3d wA =
      def.bodyA.valid() ? world.angularVelocity(def.bodyA) : Eigen::Vector3d::Zero();
  return axis.dot(world.angularVelocity(def.bodyB) - wA);
}

double anchorGap(const engine::World& world, const joints::JointDef& def) {
  return (endPose(world, def.bodyA).apply(def.frameA.anchor) -
          endPose(world, def.bodyB).apply(def.frameB.anchor))
      .norm();
}

struct Pair {
  engine::World reduced, maximal;
  geometry::ArticulationId tree;
  engine::io::UrdfMaximalIds ids;
};

Pair build(const UrdfModel& model, const Eigen::VectorXd& q) {
  engine::WorldSettings settings;
  settings.solve.options.tolerance = 1e-12;  // joint rows solved tightly: compare dynamics
  // One step's velocity change is exactly h qdd(q0) with semi-implicit Euler (the Runge-Kutta
  // default averages qdd over the step): compare the instantaneous accelerations.
  settings.treeIntegrator = engine::TreeIntegrator::SemiImplicitEuler;
  Pair p{engine::World(settings), engine::World(settings), {}, {}};
  engine::ArticulationDesc desc = engine::io::toArticulationDesc(model, "tree");
  desc.q = q;
  p.tree = p.reduced.createArticulation(desc);
  const engine::io::UrdfMaximal maximal = engine::io::toMaximal(model, "free", q);
  p.ids = engine::io::createMaximal(p.maximal, maximal);
  return p;
}

void compareAccelerations(const std::string& file) {
  const UrdfModel model = load(file);
  const joints::tree::Articulation tree = engine::io::toArticulation(model);
  const Eigen::VectorXd q = bent(tree);
  const Eigen::VectorXd qdd = joints::tree::forwardDynamics(
      tree, q, Eigen::VectorXd::Zero(tree.nv()), Eigen::VectorXd::Zero(tree.nv()));
  Pair p = build(model, q);
  ASSERT_EQ(p.ids.joints.size(), static_cast<std::size_t>(tree.nv()));
  const double h = 1e-4;
  p.reduced.step(h);
  p.maximal.step(h);
  double worst = 0.0, worstReduced = 0.0;
  for (std::size_t j = 0; j < p.ids.joints.size(); ++j) {
    const double rate = hingeRate(p.maximal, p.maximal.joint(p.ids.joints[j]));
    worst = std::max(worst, std::abs(rate / h - qdd[static_cast<Eigen::Index>(j)]));
    worstReduced = std::max(worstReduced, std::abs(p.reduced.articulations().qd(p.tree)[j] / h -
                                                   qdd[static_cast<Eigen::Index>(j)]));
  }
  const double scale = qdd.cwiseAbs().maxCoeff();
  std::cout << file << ": " << tree.nv() << " joints, max |qdd| " << scale
            << " rad/s^2; maximal vs ABA: max error " << worst / scale << " relative; tree vs ABA "
            << worstReduced / scale << "\n";
  EXPECT_LT(worst, 1e-6 * scale);
  EXPECT_LT(worstReduced, 1e-12 * scale);
}

TEST(UrdfMaximal, DoublePendulumAccelerationsMatchTheTree) {
  compareAccelerations("double_pendulum/double_pendulum.urdf");
}

TEST(UrdfMaximal, KukaAccelerationsMatchTheTree) {
  compareAccelerations("kuka_iiwa/model.urdf");
}

/// Largest joint-angle difference between the two forms and largest joint anchor gap of the
/// maximal one over `duration` at step h.
std::pair<double, double> trajectoryDifference(const UrdfModel& model, double h, double duration) {
  const joints::tree::Articulation tree = engine::io::toArticulation(model);
  Pair p = build(model, bent(tree));
  double worstAngle = 0.0, worstGap = 0.0;
  const auto steps = static_cast<int>(std::lround(duration / h));
  for (int k = 0; k < steps; ++k) {
    p.reduced.step(h);
    p.maximal.step(h);
    for (std::size_t j = 0; j < p.ids.joints.size(); ++j) {
      const joints::JointDef& def = p.maximal.joint(p.ids.joints[j]);
      const double d = std::remainder(
          hingeAngle(p.maximal, def) - p.reduced.articulations().q(p.tree)[j], 2.0 * M_PI);
      worstAngle = std::max(worstAngle, std::abs(d));
      worstGap = std::max(worstGap, anchorGap(p.maximal, def));
    }
  }
  return {worstAngle, worstGap};
}

TEST(UrdfMaximal, DoublePendulumTrajectoryAndClosure) {
  // The two forms integrate different coordinates with first-order schemes (and the double
  // pendulum is chaotic): their difference is O(h) over a short time, so it must halve with h.
  const UrdfModel model = load("double_pendulum/double_pendulum.urdf");
  const double duration = 0.25;
  const auto [coarse, gapCoarse] = trajectoryDifference(model, 1e-3, duration);
  const auto [fine, gapFine] = trajectoryDifference(model, 5e-4, duration);
  std::cout << "double pendulum, " << duration << " s: max angle difference maximal vs tree "
            << coarse << " rad (h = 1 ms), " << fine << " rad (h = 0.5 ms); max joint anchor gap "
            << std::max(gapCoarse, gapFine) << " m\n";
  EXPECT_LT(coarse, 2e-2);
  EXPECT_LT(fine, 0.65 * coarse);  // first order: ~0.5
  EXPECT_LT(std::max(gapCoarse, gapFine), 1e-6);
}

TEST(UrdfMaximal, SceneEntryMakesBodiesAndJoints) {
  const std::string text = R"({"urdf": [{"file": "kuka_iiwa/model.urdf", "name": "kuka",
      "coordinates": "maximal", "motors": {"lbr_iiwa_joint_1": {"mode": "velocity",
      "target": 0.5, "max_effort": 50}}}]})";
  const engine::io::Scene scene = engine::io::parseScene(text, "kuka.json", kCorpus);
  EXPECT_TRUE(scene.articulations.empty());
  ASSERT_EQ(scene.bodies.size(), 8u);  // static base + 7 links
  ASSERT_EQ(scene.joints.size(), 7u);
  EXPECT_EQ(scene.bodies[0].motionType, geometry::MotionType::Static);
  EXPECT_EQ(scene.bodies[1].name, "kuka/lbr_iiwa_link_1");
  EXPECT_TRUE(scene.joints[0].def.motor.enabled);
  EXPECT_EQ(scene.joints[0].def.motor.maxForce, 50.0);
  engine::World world = engine::io::buildWorld(scene);
  for (int k = 0; k < 20; ++k) world.step(0.005);
  const double rate = hingeRate(world, world.joint(geometry::JointId{0, 0}));
  std::cout << "maximal kuka, velocity motor 0.5 rad/s on joint 1: rate " << rate << "\n";
  EXPECT_NEAR(rate, 0.5, 1e-3);

  auto fails = [&](const std::string& entry, const std::string& expected) {
    try {
      (void)engine::io::parseScene(R"({"urdf": [)" + entry + "]}", "bad.json", kCorpus);
      ADD_FAILURE() << "expected an error for " << entry;
    } catch (const engine::CoulombError& e) {
      EXPECT_NE(std::string(e.what()).find(expected), std::string::npos) << e.what();
    }
  };
  fails(R"({"file": "kuka_iiwa/model.urdf", "coordinates": "maximal", "hold": true})",
        "velocity motors only");
  fails(R"({"file": "kuka_iiwa/model.urdf", "coordinates": "maximal",
            "torques": {"lbr_iiwa_joint_1": 1}})",
        "need reduced coordinates");
  fails(R"({"file": "kuka_iiwa/model.urdf", "coordinates": "minimal"})",
        "expected \"reduced\" or \"maximal\"");
}

TEST(UrdfMaximal, OneFileSceneOnAFloor) {  // `coulomb run robot.urdf --maximal --limp`
  const auto file = kCorpus / "kuka_iiwa/model.urdf";
  const engine::io::Scene scene =
      engine::io::urdfFileScene(file, engine::io::UrdfBase::Fixed, false, {}, true);
  ASSERT_EQ(scene.bodies.size(), 9u);  // floor, static base, 7 links
  ASSERT_EQ(scene.joints.size(), 7u);
  EXPECT_EQ(scene.joints[0].bodyA, 1);
  EXPECT_EQ(scene.joints[0].bodyB, 2);
  engine::World world = engine::io::buildWorld(scene);
  for (int k = 0; k < 20; ++k) world.step(0.005);
  for (std::size_t j = 0; j < world.jointCount(); ++j)
    EXPECT_LT(anchorGap(world, world.joint(geometry::JointId{static_cast<std::uint32_t>(j), 0})),
              1e-4);
  try {
    (void)engine::io::urdfFileScene(file, engine::io::UrdfBase::Fixed, true, {}, true);
    ADD_FAILURE() << "expected an error";
  } catch (const engine::CoulombError& e) {
    EXPECT_NE(std::string(e.what()).find("--limp"), std::string::npos) << e.what();
  }
}

TEST(UrdfMaximal, BadConfigurationIsNamed) {
  const UrdfModel model = load("double_pendulum/double_pendulum.urdf");
  try {
    (void)engine::io::toMaximal(model, "dp", Eigen::VectorXd::Zero(5));
    ADD_FAILURE() << "expected an error";
  } catch (const engine::CoulombError& e) {
    EXPECT_NE(std::string(e.what()).find("robot 'dp'"), std::string::npos) << e.what();
  }
  Eigen::VectorXd nan = Eigen::VectorXd::Zero(2);
  nan[1] = std::nan("");
  EXPECT_THROW((void)engine::io::toMaximal(model, "dp", nan), engine::CoulombError);
}

}  // namespace
