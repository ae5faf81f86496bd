// Articulations in the World (issue 10 items 3-4): free motion equals the standalone integrator,
// contacts on links are in one island and one problem with free bodies, an arm resting on a table
// carries its weight, a floating tree hitting a box conserves momentum, joint limits stop a
// swing, and a four-bar (tree + loop closure) keeps its closure.
#include <gtest/gtest.h>
#include <coulomb/engine/CoulombError.hpp>
#include <coulomb/engine/World.hpp>
#include <coulomb/integrators/ArticulationIntegrator.hpp>
#include <coulomb/joints/tree/TreeKinematics.hpp>

#include <Eigen/Geometry>

#include <cmath>

using namespace coulomb;
using engine::ArticulationDesc;
using engine::ArticulationLinkDesc;
using geometry::ArticulationId;
using geometry::BodyId;
using geometry::Pose;
using joints::tree::TreeJoint;

namespace {

constexpr double kG = 9.81;

geometry::SpatialInertia rodInertia(double m, const Eigen::Vector3d& com, double length) {
  return {m, com, Eigen::Matrix3d::Identity() * m * length * length / 12.0};
}

engine::ShapeDesc boxShape(const Eigen::Vector3d& half, const Eigen::Vector3d& at,
                           double mu = 0.5) {
  return {geometry::Box{half}, Pose::translation(at), {mu, 0.0}, {}};
}

/// One link on a revolute joint about y at `pivot`; the link is a 1 m bar along +x (a box of
/// half extents (0.5, 0.05, 0.05)) with its mass m at x = 0.5.
ArticulationDesc horizontalArm(const Eigen::Vector3d& pivot, double m) {
  ArticulationDesc arm;
  arm.name = "arm";
  ArticulationLinkDesc link;
  link.name = "upper";
  link.joint = TreeJoint::revolute("shoulder", Pose::translation(pivot), Eigen::Vector3d::UnitY());
  link.inertia = rodInertia(m, {0.5, 0, 0}, 1.0);
  link.shapes.push_back(boxShape({0.5, 0.05, 0.05}, {0.5, 0, 0}));
  arm.links.push_back(link);
  return arm;
}

BodyId addStaticBox(engine::World& world, const Eigen::Vector3d& centre,
                    const Eigen::Vector3d& half) {
  engine::BodyDesc table;
  table.name = "table";
  table.motionType = geometry::MotionType::Static;
  table.pose = Pose::translation(centre);
  table.shapes.push_back(boxShape(half, Eigen::Vector3d::Zero()));
  return world.createBody(table);
}

}  // namespace

TEST(WorldArticulation, FreeMotionEqualsTheStandaloneIntegrator) {
  // Without rows the step is the tree integrator of the settings, bit for bit.
  for (const engine::TreeIntegrator integrator :
       {engine::TreeIntegrator::RungeKutta, engine::TreeIntegrator::SemiImplicitEuler}) {
    engine::WorldSettings settings;
    settings.treeIntegrator = integrator;
    engine::World world(settings);
    ArticulationDesc desc = horizontalArm({0, 0, 2}, 1.0);
    desc.links[0].shapes.clear();
    const ArticulationId id = world.createArticulation(desc);
    Eigen::VectorXd q = Eigen::VectorXd::Zero(1), qd = Eigen::VectorXd::Zero(1);
    const Eigen::VectorXd tau = Eigen::VectorXd::Zero(1);
    joints::tree::Articulation model({{"upper", -1, desc.links[0].joint, *desc.links[0].inertia}});
    joints::tree::AbaWorkspace aba;
    integrators::TreeStepScratch scratch;
    double largest = 0.0;
    for (int k = 0; k < 200; ++k) {
      world.step(0.01);
      if (integrator == engine::TreeIntegrator::RungeKutta)
        integrators::rungeKuttaStep(model, q, qd, tau, 0.01, aba, scratch);
      else
        integrators::stepArticulation(model, q, qd, tau, 0.01);
      largest = std::max(largest, std::abs(q[0]));
    }
    EXPECT_NEAR(world.articulations().q(id)[0], q[0], 1e-14);
    EXPECT_NEAR(world.articulations().qd(id)[0], qd[0], 1e-14);
    EXPECT_GT(largest, 1.5);  // it swung down from horizontal
    // The proxy follows the link: its pose is the link frame from forward kinematics.
    const BodyId proxy = world.articulations().linkBody(id, 0);
    EXPECT_EQ(world.name(proxy), "arm/upper");
    EXPECT_TRUE(world.pose(proxy).position.isApprox(Eigen::Vector3d(0, 0, 2)));
    EXPECT_NEAR(world.pose(proxy).rotation.angularDistance(Eigen::Quaterniond(
                    Eigen::AngleAxisd(world.articulations().q(id)[0], Eigen::Vector3d::UnitY()))),
                0.0, 1e-12);
  }
}

TEST(WorldArticulation, ArmRestingOnATableStaysAtRestAndCarriesItsWeight) {
  engine::WorldSettings settings;
  settings.solve.options.tolerance = 1e-10;
  engine::World world(settings);
  const double m = 2.0, h = 0.01;
  const Eigen::Vector3d pivot(0, 0, 1);
  const ArticulationId arm = world.createArticulation(horizontalArm(pivot, m));
  // Table under the outer 0.4 m of the bar; its top touches the bar's underside (z = 0.95).
  addStaticBox(world, {1.0, 0, 0.75}, {0.2, 0.5, 0.2});
  for (int k = 0; k < 300; ++k) {
    const engine::StepReport report = world.step(h);
    for (const auto& island : report.islands)
      ASSERT_EQ(island.status, solvers::SolverStatus::Converged)
          << "step " << k << ": " << island.solve.message;
    if (k < 5) continue;
    ASSERT_EQ(report.islands.size(), 1u) << "step " << k;
    ASSERT_GE(report.islands.front().contacts, 2u);
    // Moment balance about the shoulder: the contact impulses' moment cancels the weight's,
    // m g 0.5 cos(q) h about +y (normal and friction impulses, on the arm's side).
    double moment = 0.0;
    const BodyId proxy = world.articulations().linkBody(arm, 0);
    for (const auto& manifold : world.contacts()) {
      const double onArm = manifold.bodyB == proxy ? 1.0 : -1.0;
      for (const auto& p : manifold.activePoints()) {
        const Eigen::Vector3d impulse = p.normalImpulse * manifold.normal +
                                        p.tangentImpulse[0] * manifold.tangent1 +
                                        p.tangentImpulse[1] * manifold.tangent2;
        moment += onArm * (p.position - pivot).cross(impulse).y();
      }
    }
    const double weight = m * kG * 0.5 * std::cos(world.articulations().q(arm)[0]) * h;
    EXPECT_NEAR(moment, -weight, 1e-6 * weight) << "step " << k;
  }
  EXPECT_NEAR(world.articulations().q(arm)[0], 0.0, 1e-3);
  EXPECT_NEAR(world.articulations().qd(arm)[0], 0.0, 1e-6);
}

TEST(WorldArticulation, FloatingTreeHittingAFreeBoxConservesMomentum) {
  engine::WorldSettings settings;
  settings.gravity.setZero();
  engine::World world(settings);
  // Floating base (a 0.2 m cube, 3 kg) with a 1 kg bar behind it on a revolute joint, flying
  // along +x into a free box on the same line: the contact pushes through the COM line, so the
  // tree gains no rotation and free flight adds no drift; any change of the total momentum is
  // the contact's.
  ArticulationDesc tree;
  tree.name = "tree";
  ArticulationLinkDesc base;
  base.name = "base";
  base.joint = TreeJoint::floating("free");
  base.inertia = geometry::SpatialInertia{3.0, Eigen::Vector3d::Zero(),
                                          Eigen::Matrix3d::Identity() * 3.0 * 0.08 / 12.0};
  base.shapes.push_back(boxShape({0.1, 0.1, 0.1}, Eigen::Vector3d::Zero(), 0.3));
  ArticulationLinkDesc bar;
  bar.name = "bar";
  bar.parent = 0;
  bar.joint =
      TreeJoint::revolute("hinge", Pose::translation({-0.1, 0, 0}), Eigen::Vector3d::UnitY());
  bar.inertia = rodInertia(1.0, {-0.3, 0, 0}, 0.6);
  bar.shapes.push_back(boxShape({0.3, 0.03, 0.03}, {-0.3, 0, 0}, 0.3));
  tree.links = {base, bar};
  Eigen::VectorXd qd = Eigen::VectorXd::Zero(7);
  qd.segment<3>(3) = Eigen::Vector3d(2.0, 0.0, 0.0);  // base twist: velocity of its origin
  tree.qd = qd;
  const ArticulationId id = world.createArticulation(tree);

  engine::BodyDesc box;
  box.name = "box";
  box.pose = Pose::translation({0.6, 0.0, 0.0});
  box.shapes.push_back(boxShape({0.15, 0.15, 0.15}, Eigen::Vector3d::Zero(), 0.3));
  box.mass = geometry::SpatialInertia{1.5, Eigen::Vector3d::Zero(),
                                      Eigen::Matrix3d::Identity() * 1.5 * 0.09 / 12.0};
  const BodyId boxId = world.createBody(box);

  auto momentum = [&]() {
    const joints::tree::Articulation& model = world.articulations().model(id);
    const auto kin = joints::tree::forwardKinematics(model, world.articulations().q(id));
    geometry::Vector6d total =
        joints::tree::spatialMomentum(model, kin, world.articulations().qd(id));
    const double mb = world.massProperties(boxId).mass;
    const Eigen::Vector3d p = mb * world.linearVelocity(boxId);
    total.head<3>() += p;
    total.tail<3>() +=
        world.state().angularMomentum(boxId.index) + world.pose(boxId).position.cross(p);
    return total;
  };
  const geometry::Vector6d before = momentum();
  bool touched = false;
  for (int k = 0; k < 60; ++k) {
    const engine::StepReport report = world.step(0.005);
    for (const auto& island : report.islands) {
      if (island.contacts == 0) continue;
      touched = true;
      EXPECT_EQ(report.islands.size(), 1u);  // the tree and the box: one island, one problem
    }
  }
  ASSERT_TRUE(touched);
  const geometry::Vector6d after = momentum();
  EXPECT_NEAR((after.head<3>() - before.head<3>()).norm(), 0.0, 1e-9 * before.head<3>().norm());
  EXPECT_NEAR((after.tail<3>() - before.tail<3>()).norm(), 0.0, 1e-8);
  EXPECT_GT(world.linearVelocity(boxId).x(), 0.5);  // the box was pushed
}

TEST(WorldArticulation, JointLimitStopsASwing) {
  engine::World world;
  ArticulationDesc desc = horizontalArm({0, 0, 2}, 1.0);
  desc.links[0].shapes.clear();
  desc.links[0].joint.lower = -0.4;
  desc.links[0].joint.upper = 0.3;
  desc.qd = Eigen::VectorXd::Constant(1, -4.0);  // swings up (towards negative angles)
  const ArticulationId id = world.createArticulation(desc);
  double lowest = 0.0, highest = 0.0, restingRate = 0.0;
  for (int k = 0; k < 300; ++k) {
    world.step(0.01);
    lowest = std::min(lowest, world.articulations().q(id)[0]);
    highest = std::max(highest, world.articulations().q(id)[0]);
    if (k >= 200) restingRate = std::max(restingRate, std::abs(world.articulations().qd(id)[0]));
  }
  EXPECT_NEAR(lowest, -0.4, 1e-3);  // reached the lower stop, not beyond
  EXPECT_NEAR(highest, 0.3, 1e-3);  // gravity swings it down onto the upper stop
  EXPECT_NEAR(world.articulations().q(id)[0], 0.3, 1e-3);  // and it rests there
  // Over the last second: the speculative limit row leaves a limit cycle of about 1e-6 rad/s
  // (1e-8 rad) with either tree integrator, whose phase decided the single-step check before.
  EXPECT_LT(restingRate, 2e-6);
}

namespace {

// Parallelogram four-bar: crank (link 0) and rocker (link 2) of length L hinged to the world d
// apart, coupler (link 1) of length d hinged to the crank's tip. Its far end meets the rocker's
// tip; the closure is added by each test.
constexpr double kCrank = 0.5, kSpan = 0.8, kTheta = 0.4;

ArticulationDesc fourBarTree() {
  const double L = kCrank, d = kSpan;
  const Eigen::Vector3d y = Eigen::Vector3d::UnitY();
  ArticulationDesc fourBar;
  fourBar.name = "fourbar";
  fourBar.links = {{"crank",
                    -1,
                    TreeJoint::revolute("a", Pose::identity(), y),
                    rodInertia(1.0, {0, 0, L / 2}, L),
                    {},
                    {}},
                   {"coupler",
                    0,
                    TreeJoint::revolute("b", Pose::translation({0, 0, L}), y),
                    rodInertia(1.0, {d / 2, 0, 0}, d),
                    {},
                    {}},
                   {"rocker",
                    -1,
                    TreeJoint::revolute("c", Pose::translation({d, 0, 0}), y),
                    rodInertia(1.0, {0, 0, L / 2}, L),
                    {},
                    {}}};
  fourBar.q = Eigen::Vector3d(kTheta, -kTheta, kTheta);
  return fourBar;
}

/// Steps 2 s; returns the largest closure gap and checks the parallelogram's motion.
double runFourBar(engine::World& world, ArticulationId id) {
  auto gap = [&]() {
    const auto& a = world.articulations();
    return (a.linkPose(id, 1).apply({kSpan, 0, 0}) - a.linkPose(id, 2).apply({0, 0, kCrank}))
        .norm();
  };
  EXPECT_LT(gap(), 1e-12);
  double worst = 0.0, swing = 0.0;
  for (int k = 0; k < 400; ++k) {
    world.step(0.005);
    worst = std::max(worst, gap());
    swing = std::max(swing, std::abs(world.articulations().q(id)[0] - kTheta));
  }
  EXPECT_GT(swing, 0.3);  // it moved (falls through the bottom and swings)
  // Parallelogram: the rocker follows the crank and the coupler stays horizontal.
  const Eigen::VectorXd& q = world.articulations().q(id);
  EXPECT_NEAR(q[2], q[0], 5e-3);
  EXPECT_NEAR(q[1], -q[0], 5e-3);
  return worst;
}

}  // namespace

TEST(WorldArticulation, FourBarWithALoopClosureKeepsItsClosure) {
  // Planar point closure (x and z; y is already fixed by the hinges, a third row is redundant).
  ArticulationDesc fourBar = fourBarTree();
  fourBar.loopClosures.push_back({1, {kSpan, 0, 0}, 2, {0, 0, kCrank}, {true, false, true}});
  engine::World world;
  const ArticulationId id = world.createArticulation(fourBar);
  EXPECT_LT(runFourBar(world, id), 2e-3);
}

TEST(WorldArticulation, FourBarClosedByAMaximalBallJointKeepsItsClosure) {
  // The same loop closed by a World ball joint (joints/, maximal coordinates) between the two
  // link proxies: its rows are ordinary row blocks on the proxies, so they reach the tree.
  engine::World world;
  const ArticulationId id = world.createArticulation(fourBarTree());
  engine::JointDesc ball;
  ball.name = "closure";
  ball.type = joints::JointType::Ball;
  ball.bodyA = world.articulations().linkBody(id, 1);
  ball.bodyB = world.articulations().linkBody(id, 2);
  ball.frameA.anchor = {kSpan, 0, 0};
  ball.frameB.anchor = {0, 0, kCrank};
  joints::Stabilization baumgarte;  // proxies are kinematic bodies: a position-level
  baumgarte.method = joints::StabilizationMethod::Baumgarte;  // correction cannot move them
  ball.stabilization = baumgarte;
  world.createJoint(ball);
  EXPECT_LT(runFourBar(world, id), 2e-3);
}

TEST(WorldArticulation, BadDescriptionsThrowAndAddNothing) {
  engine::World world;
  ArticulationDesc desc = horizontalArm({0, 0, 1}, 1.0);
  desc.links[0].parent = 0;
  EXPECT_THROW(world.createArticulation(desc), engine::CoulombError);
  desc = horizontalArm({0, 0, 1}, 1.0);
  desc.q = Eigen::VectorXd::Constant(2, 0.0);
  EXPECT_THROW(world.createArticulation(desc), engine::CoulombError);
  desc.q.reset();
  desc.links[0].shapes.push_back(boxShape({-1, 1, 1}, Eigen::Vector3d::Zero()));
  EXPECT_THROW(world.createArticulation(desc), engine::CoulombError);
  EXPECT_EQ(world.bodyCount(), 0u);
  EXPECT_EQ(world.articulations().count(), 0u);
  const ArticulationId id = world.createArticulation(horizontalArm({0, 0, 1}, 1.0));
  EXPECT_THROW(world.removeBody(world.articulations().linkBody(id, 0)), engine::CoulombError);
  EXPECT_THROW(
      world.setArticulationState(id, Eigen::VectorXd::Constant(1, NAN), Eigen::VectorXd::Zero(1)),
      engine::CoulombError);
}
