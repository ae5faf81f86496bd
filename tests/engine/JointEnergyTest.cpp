// The energy projection of islands of ideal joints (integrators/EnergyProjection.hpp,
// joints::PredictedStateSettings::energy; docs/tuning.md, "Chains keep their energy"): the A6
// chains of docs/scene-specifications.md keep their energy at dt 0.01, the pendulum keeps its
// phase, a free island keeps its momentum, and islands with a driver, a limit or an applied force
// are left alone.
#include <gtest/gtest.h>
#include <coulomb/engine/JointStage.hpp>
#include <coulomb/integrators/EnergyProjection.hpp>
#include <coulomb/io/SceneLoader.hpp>

#include "JointTestScenes.hpp"
#include "SceneErrorTestHelpers.hpp"

#include <algorithm>
#include <cstdio>
#include <limits>
#include <string>
#include <tuple>

using namespace coulomb;
using namespace coulomb::testing;

namespace {

engine::WorldSettings settingsWith(joints::EnergyTarget energy) {
  engine::WorldSettings s;
  s.jointStabilization.predictedState.energy = energy;
  return s;
}

struct ChainRun {
  double gap = 0.0;        // [m] largest anchor gap over the run
  double endDrift = 0.0;   // (E(T) - E0) / S
  double maxDrift = 0.0;   // largest (E - E0) / S
  double minDrift = 0.0;   // smallest (E - E0) / S
  int projectedSteps = 0;  // steps on which the island was projected
};

/// docs/scene-specifications.md A6: N links released horizontal, S = m g L N^2 / 2.
ChainRun runChain(int links, joints::EnergyTarget energy, double h, int steps) {
  JointedScene scene(settingsWith(energy));
  buildChain(scene, links);
  const double released = 0.1 * kG * 0.1 * links * links / 2.0;
  const double e0 = scene.world.mechanicalEnergy();
  ChainRun run;
  for (int k = 0; k < steps; ++k) {
    const engine::StepReport& report = scene.world.step(h);
    run.projectedSteps += report.joints.energyProjections;
    run.gap = std::max(run.gap, maxAnchorGap(scene.world, scene.joints));
    const double drift = (scene.world.mechanicalEnergy() - e0) / released;
    run.maxDrift = std::max(run.maxDrift, drift);
    run.minDrift = std::min(run.minDrift, drift);
    run.endDrift = drift;
  }
  std::printf(
      "chain_%d %s dt %g, %d steps: gap %.2e m, E/S end %+.4f, min %+.4f, max %+.4f, "
      "projected %d\n",
      links, joints::energyTargetName(energy), h, steps, run.gap, run.endDrift, run.minDrift,
      run.maxDrift, run.projectedSteps);
  return run;
}

}  // namespace

// A6 at dt 0.01 over 10 s: the step alone loses 40-90 % of the released energy (chaotic in the
// figure, never less than a third); with the modified target (the default) the energy ends within
// a few % of its start and never drifts (E itself swings by O(h) around E~: up to +7 % of S at a
// whip of chain_10, measured), and the joints stay closed.
TEST(JointEnergy, ChainsKeepTheirEnergyAtDt001WithTheModifiedTarget) {
  const ChainRun plain = runChain(10, joints::EnergyTarget::None, 0.01, 1000);
  EXPECT_LT(plain.endDrift, -0.3) << "the step without projection loses a third or more";
  EXPECT_EQ(plain.projectedSteps, 0);
  for (const int links : {10, 50}) {
    const ChainRun run = runChain(links, joints::EnergyTarget::Modified, 0.01, 1000);
    EXPECT_LT(run.gap, 1e-6) << links;
    EXPECT_GT(run.minDrift, -0.05) << links;
    EXPECT_LT(run.maxDrift, 0.1) << links;
    EXPECT_LT(std::abs(run.endDrift), 0.03) << links;
    EXPECT_GT(run.projectedSteps, 900) << links << ": turning points may be skipped, little else";
  }
}

// At dt 0.0025 the step alone gains energy on chain_10 (+30 % measured); projected, it does not.
TEST(JointEnergy, ChainDoesNotGainEnergyAtDt00025) {
  const ChainRun run = runChain(10, joints::EnergyTarget::Modified, 0.0025, 4000);
  EXPECT_LT(run.maxDrift, 0.02);
  EXPECT_GT(run.minDrift, -0.02);
  EXPECT_LT(run.gap, 1e-6);
}

// The exact target pins E itself: it never leaves its start (up to steps left alone at a turning
// point, where scaling the speeds is no model of the error), on the A6 chains at dt 0.01 and
// 0.0025 (issue 25 item 1: never above E(0) + 1e-6 S), with the joints closed.
TEST(JointEnergy, ExactTargetPinsTheEnergy) {
  for (const auto& [links, h, steps] :
       {std::tuple{10, 0.01, 1000}, std::tuple{50, 0.01, 1000}, std::tuple{10, 0.0025, 4000}}) {
    const ChainRun run = runChain(links, joints::EnergyTarget::Exact, h, steps);
    EXPECT_LT(run.maxDrift, 1e-6) << links << " " << h;
    EXPECT_GT(run.minDrift, -1e-6) << links << " " << h;
    EXPECT_LT(run.gap, 1e-6) << links << " " << h;
  }
}

namespace {

struct PeriodRun {
  double relativeError = 0.0;  // measured period / expected - 1
  double maxDrift = 0.0;       // largest (E - E0) / S, S = m g l (the pendulum) or released energy
  int projected = 0;           // steps on which the island was projected
};

// The period of the first body's angle theta1 = atan2(x, -z) from its sign changes over 1 000
// steps of dt 0.01 (every half period; averaged over consecutive full periods).
PeriodRun measurePeriod(JointedScene& scene, double expected, double released) {
  std::vector<double> crossings;
  const double e0 = scene.world.mechanicalEnergy();
  const auto angle = [&] {
    const Eigen::Vector3d c = scene.world.pose(scene.bodies[0]).position;
    return std::atan2(c.x(), -c.z());
  };
  double previous = angle();
  PeriodRun run;
  for (int k = 1; k <= 1000; ++k) {
    run.projected += scene.world.step(0.01).joints.energyProjections;
    run.maxDrift = std::max(run.maxDrift, (scene.world.mechanicalEnergy() - e0) / released);
    const double theta = angle();
    if ((theta < 0) != (previous < 0))
      crossings.push_back(0.01 * (k - 1) + 0.01 * previous / (previous - theta));
    previous = theta;
  }
  EXPECT_GE(crossings.size(), 3u);
  if (crossings.size() < 3) return run;
  double period = 0.0;
  for (std::size_t i = 0; i + 2 < crossings.size(); ++i) period += crossings[i + 2] - crossings[i];
  period /= static_cast<double>(crossings.size() - 2);
  run.relativeError = period / expected - 1.0;
  return run;
}

PeriodRun pendulumPeriod(joints::EnergyTarget energy) {
  JointedScene scene(settingsWith(energy));
  buildPendulum(scene);
  const PeriodRun run = measurePeriod(scene, 2.369025573, kG);  // B8: 1 kg, 1 m
  std::printf("pendulum %s: period_rel_err %.3g, E above E0 at most %.2e S, projected steps %d\n",
              joints::energyTargetName(energy), run.relativeError, run.maxDrift, run.projected);
  return run;
}

}  // namespace

// B8 pendulum, released horizontal: with the modified target its period stays within the B8 bound
// (the first-order modified energy is what the step keeps where it resolves the motion).
TEST(JointEnergy, PendulumKeepsItsPeriodWithTheModifiedTarget) {
  const PeriodRun run = pendulumPeriod(joints::EnergyTarget::Modified);
  EXPECT_LT(std::abs(run.relativeError), 1e-3);
  EXPECT_GT(run.projected, 900);
}

// The exact target takes the symmetric step (half kicks around the position update, RATTLE):
// pinning E on it moves a period by O(h^2) (measured -2.2e-4 on B8), where pinning E on the
// kick-drift step moved it by O(h) (2.3e-3, beyond the B8 bound of 1e-3). E never rises above
// its start. The B9 double pendulum's normal modes (amplitudes as WorldJointTest): the slow mode
// within the B9 bound (measured -1.8e-4), the fast one (h omega = 0.10) at -1.34e-3, above it:
// pinning E on a second-order step costs a mode (h omega)^2 / 8 of its period, against 5.4e-5
// with the modified target (docs/tuning.md, "Chains keep their energy").
TEST(JointEnergy, ExactTargetKeepsThePeriodsThroughTheSymmetricStep) {
  const PeriodRun pendulum = pendulumPeriod(joints::EnergyTarget::Exact);
  EXPECT_LT(std::abs(pendulum.relativeError), 1e-3);
  EXPECT_LT(pendulum.maxDrift, 1e-6);
  EXPECT_GT(pendulum.projected, 900);
  struct Mode {
    double theta2, period, bound;
  };
  for (const Mode mode : {Mode{0.0142419, 1.654864, 1e-3}, Mode{-0.0210646, 0.608693, 2e-3}}) {
    JointedScene scene(settingsWith(joints::EnergyTarget::Exact));
    buildDoublePendulum(scene, 0.01, mode.theta2);
    const PeriodRun run = measurePeriod(scene, mode.period, 2.0 * kG * 0.5);
    std::printf("double pendulum mode %.4f s, exact: period_rel_err %.3g, E above E0 %.2e\n",
                mode.period, run.relativeError, run.maxDrift);
    EXPECT_LT(std::abs(run.relativeError), mode.bound) << mode.period;
    EXPECT_LT(run.maxDrift, 1e-6) << mode.period;
  }
}

// A free island under `exact` (a ragdoll in flight): the symmetric step's half kicks are the same
// on every body and its velocity projection puts only internal impulses, so the momentum changes
// by exactly M g t, the angular momentum about the centre of mass is kept (gravity has no torque
// about it), E stays at its start and the joint stays closed.
TEST(JointEnergy, FreeIslandUnderTheSymmetricStepKeepsItsMomentaAndEnergy) {
  JointedScene scene(settingsWith(joints::EnergyTarget::Exact));
  const Eigen::Vector3d xa(0, 0, 0), xb(0.5, 0, 0), anchor(0.25, 0, 0);
  const Eigen::Vector3d wa(0.3, -1.2, 2.0), wb(-1.5, 0.4, 0.7), va(0.5, 0.2, -0.4);
  const Eigen::Vector3d vb = va + wa.cross(anchor - xa) - wb.cross(anchor - xb);
  scene.bodies.push_back(addBody(scene.world, "a", geometry::Pose::translation(xa), 1.0,
                                 Eigen::Vector3d(0.01, 0.02, 0.03)));
  scene.bodies.push_back(addBody(scene.world, "b", geometry::Pose::translation(xb), 0.5,
                                 Eigen::Vector3d(0.004, 0.01, 0.012)));
  scene.joints.push_back(scene.world.createJoint(jointDesc(
      joints::JointType::Ball, scene.bodies[0], scene.bodies[1], anchor - xa, anchor - xb)));
  scene.world.setVelocity(scene.bodies[0], va, wa);
  scene.world.setVelocity(scene.bodies[1], vb, wb);
  const auto momenta = [&](Eigen::Vector3d& p, Eigen::Vector3d& l) {
    const geometry::BodyState& state = scene.world.state();
    double mass = 0.0;
    Eigen::Vector3d centre = Eigen::Vector3d::Zero();
    for (const geometry::BodyId id : scene.bodies) {
      mass += 1.0 / state.inverseMasses[id.index];
      centre += state.poses[id.index].position / state.inverseMasses[id.index];
    }
    centre /= mass;
    p.setZero();
    l.setZero();
    for (const geometry::BodyId id : scene.bodies) {
      const Eigen::Vector3d pi = state.linearVelocities[id.index] / state.inverseMasses[id.index];
      p += pi;
      l += (state.poses[id.index].position - centre).cross(pi) + state.angularMomentum(id.index);
    }
  };
  Eigen::Vector3d p0, l0, p, l;
  momenta(p0, l0);
  const double e0 = scene.world.mechanicalEnergy();
  double energyError = 0.0, gap = 0.0, momentumError = 0.0, angularError = 0.0;
  int projected = 0;
  for (int k = 1; k <= 300; ++k) {
    projected += scene.world.step(0.01).joints.energyProjections;
    momenta(p, l);
    momentumError =
        std::max(momentumError, (p - p0 - 1.5 * 0.01 * k * Eigen::Vector3d(0, 0, -kG)).norm());
    angularError = std::max(angularError, (l - l0).norm());
    energyError = std::max(energyError, std::abs(scene.world.mechanicalEnergy() - e0));
    gap = std::max(gap, maxAnchorGap(scene.world, scene.joints));
  }
  std::printf(
      "free island, exact: momentum %.2e, angular momentum %.2e, energy %.2e J, gap %.2e m, "
      "projected %d\n",
      momentumError, angularError, energyError, gap, projected);
  EXPECT_LT(momentumError, 1e-10);
  EXPECT_LT(angularError, 1e-8);
  EXPECT_LT(energyError, 1e-7);  // (the joints' tolerance leaves ~1e-9 J unresolved)
  EXPECT_LT(gap, 1e-9);
}

// A free island (no joint to the world): the projection scales only the motion relative to the
// island's rigid motion, so momentum and angular momentum about the centre of mass are kept, the
// joint's anchors keep moving together, and the modified energy reaches the target.
TEST(JointEnergy, ProjectionKeepsMomentumAndTheJointOfAFreeIsland) {
  geometry::BodyState state;
  const Eigen::Vector3d xa(0.1, -0.2, 0.3), xb(0.6, 0.1, 0.2), anchor(0.35, 0.0, 0.3);
  const Eigen::Vector3d wa(0.3, -1.2, 2.0), wb(-1.5, 0.4, 0.7), va(0.5, 0.2, -0.4);
  // B's velocity such that both bodies' anchor points move alike (a ball joint at `anchor`).
  const Eigen::Vector3d vb = va + wa.cross(anchor - xa) - wb.cross(anchor - xb);
  const Eigen::Quaterniond qa(Eigen::AngleAxisd(0.4, Eigen::Vector3d(1, 2, 3).normalized()));
  const Eigen::Quaterniond qb(Eigen::AngleAxisd(-0.9, Eigen::Vector3d(0, 1, 1).normalized()));
  state.assign(0, geometry::MotionType::Dynamic, {qa, xa}, va, wa, 2.0,
               Eigen::Vector3d(0.02, 0.03, 0.05).asDiagonal());
  state.assign(1, geometry::MotionType::Dynamic, {qb, xb}, vb, wb, 0.5,
               Eigen::Vector3d(0.004, 0.01, 0.012).asDiagonal());
  const Eigen::Vector3d g(0, 0, -9.81);
  const double h = 0.01, weight = 0.5 * h;
  const auto momenta = [&](Eigen::Vector3d& p, Eigen::Vector3d& l) {
    const double m = 2.5;
    const Eigen::Vector3d c = (2.0 * state.poses[0].position + 0.5 * state.poses[1].position) / m;
    p.setZero();
    l.setZero();
    for (std::size_t i = 0; i < 2; ++i) {
      const Eigen::Vector3d pi = state.linearVelocities[i] / state.inverseMasses[i];
      p += pi;
      l += (state.poses[i].position - c).cross(pi) + state.angularMomentum(i);
    }
  };
  const auto modified = [&] {
    double e = 0.0;
    for (std::size_t i = 0; i < 2; ++i) {
      e += integrators::bodyEnergy(state, i, g) +
           weight * g.dot(state.linearVelocities[i]) / state.inverseMasses[i];
    }
    return e;
  };
  Eigen::Vector3d p0, l0, p1, l1;
  momenta(p0, l0);
  const double target = modified() + 0.005;
  const std::vector<std::int32_t> bodies = {0, 1};
  const integrators::EnergyProjection result =
      integrators::projectEnergy(state, bodies, false, target, g, weight);
  ASSERT_TRUE(result.applied) << result.scale;
  EXPECT_NEAR(result.energyError, 0.005, 1e-12);
  EXPECT_GT(result.scale, 1.0);
  EXPECT_NEAR(modified(), target, 1e-12);
  momenta(p1, l1);
  EXPECT_LT((p1 - p0).norm(), 1e-12);
  EXPECT_LT((l1 - l0).norm(), 1e-12);
  const auto anchorVelocity = [&](std::size_t i) {
    return Eigen::Vector3d(state.linearVelocities[i] +
                           state.angularVelocities[i].cross(anchor - state.poses[i].position));
  };
  EXPECT_LT((anchorVelocity(0) - anchorVelocity(1)).norm(), 1e-12);
  // Anchored, everything scales: the same target is met with another factor.
  geometry::BodyState anchored = state;
  EXPECT_TRUE(integrators::projectEnergy(anchored, bodies, true, target + 0.01, g, weight).applied);
  // A correction the kinetic energy cannot carry is made as far as the bound on the speeds allows:
  // halved, in the right direction, with momentum still kept.
  const integrators::EnergyProjection partial =
      integrators::projectEnergy(state, bodies, false, target - 1e3, g, weight);
  EXPECT_TRUE(partial.applied);
  EXPECT_TRUE(partial.partial);
  EXPECT_EQ(partial.scale, integrators::kMinProjectionScale);
  EXPECT_LT(modified(), target);
  momenta(p1, l1);
  EXPECT_LT((p1 - p0).norm(), 1e-12);
  EXPECT_LT((l1 - l0).norm(), 1e-12);
  // A non-finite target (bad state upstream) changes nothing.
  const geometry::BodyState kept = state;
  EXPECT_FALSE(integrators::projectEnergy(state, bodies, false,
                                          std::numeric_limits<double>::quiet_NaN(), g, weight)
                   .applied);
  EXPECT_EQ(state.linearVelocities[1], kept.linearVelocities[1]);
  EXPECT_EQ(state.angularVelocities[0], kept.angularVelocities[0]);
}

// Work done on the island by something the projection cannot see: no projection.
TEST(JointEnergy, DriversLimitsAndAppliedForcesAreLeftAlone) {
  // Steps of 50 on which a 3-link chain (after `edit`) was projected; `push`: a force on link 1.
  const auto projectedSteps = [](auto&& edit, bool push) {
    JointedScene scene(settingsWith(joints::EnergyTarget::Modified));
    buildChain(scene, 3);
    edit(scene);
    int projected = 0;
    for (int k = 0; k < 50; ++k) {
      if (push) scene.world.applyForce(scene.bodies[1], {0.0, 0.0, 0.5});
      projected += scene.world.step(0.01).joints.energyProjections;
    }
    return projected;
  };
  const auto nothing = [](JointedScene&) {};
  EXPECT_GT(projectedSteps(nothing, false), 40);
  EXPECT_EQ(projectedSteps(nothing, true), 0);  // an applied force does work
  EXPECT_EQ(projectedSteps(
                [](JointedScene& s) {  // a kinematic body drives the chain's far end
                  engine::BodyDesc driver;
                  driver.name = "driver";
                  driver.motionType = geometry::MotionType::Kinematic;
                  driver.pose = geometry::Pose::translation({0.35, 0, 0});
                  driver.linearVelocity = {0, 0, 0.2};
                  const geometry::BodyId id = s.world.createBody(driver);
                  s.joints.push_back(s.world.createJoint(jointDesc(
                      joints::JointType::Ball, s.bodies[2], id, {0.05, 0, 0}, {0, 0, 0})));
                },
                false),
            0);
  EXPECT_EQ(projectedSteps(
                [](JointedScene& s) {  // a hinge with a limit (its stop is inelastic)
                  s.joints.push_back(s.world.createJoint([&] {
                    engine::JointDesc d = jointDesc(joints::JointType::Hinge, s.bodies[2], {},
                                                    {0.05, 0, 0}, {0.35, 0, 0});
                    d.limit.enabled = true;
                    d.limit.lower = -0.1;
                    d.limit.upper = 0.1;
                    return d;
                  }()));
                },
                false),
            0);
  JointedScene plain(settingsWith(joints::EnergyTarget::None));  // the default: never
  buildChain(plain, 3);
  EXPECT_EQ(plain.world.step(0.01).joints.energyProjections, 0);
}

TEST(JointEnergy, SceneFilesSetTheTargetAndNamesAreChecked) {
  const std::string scene = R"({"bodies": [{"name": "bob", "position": [1, 0, 0], "mass": 1,
      "inertia": [0.001, 0.001, 0.001]}],
      "joints": [{"type": "ball", "body_b": "bob", "anchor": [0, 0, 0]}],
      "joint_stabilization": {"energy": ENERGY}})";
  const auto withEnergy = [&](const std::string& energy) {
    std::string text = scene;
    text.replace(text.find("ENERGY"), 6, energy);
    return text;
  };
  EXPECT_EQ(engine::io::parseScene(withEnergy("\"modified\""), "test.json")
                .settings.jointStabilization.predictedState.energy,
            joints::EnergyTarget::Modified);
  EXPECT_EQ(engine::io::parseScene(withEnergy("\"exact\""), "test.json")
                .settings.jointStabilization.predictedState.energy,
            joints::EnergyTarget::Exact);
  const std::string error = coulomb::test::sceneErrorOf(withEnergy("\"modifed\""));
  EXPECT_CONTAINS(error, "test.json");
  EXPECT_CONTAINS(error, "did you mean 'modified'");
}

// The tangent velocities of a boundary (JointStage::boundaryVelocities): for velocities that
// satisfy the joints exactly (a chain turning rigidly about its anchor, a free chain in rigid
// motion) they are the bodies' own velocities, whatever order the joints are listed in; a
// prismatic joint is not covered.
TEST(JointEnergy, BoundaryVelocitiesOfJointConsistentMotionAreTheVelocities) {
  geometry::BodyState state;
  engine::JointStage stage;
  const Eigen::Vector3d omega(0.3, -1.1, 0.7);
  std::vector<std::int32_t> items;
  for (int i = 0; i < 3; ++i) {
    const Eigen::Vector3d x((i + 0.5) * 0.1, 0.02 * i, 0.0);
    state.assign(static_cast<std::size_t>(i), geometry::MotionType::Dynamic,
                 geometry::Pose::translation(x), omega.cross(x), omega, 0.1,
                 Eigen::Vector3d(1e-5, 1e-4, 1e-4).asDiagonal());
    joints::JointDef def;
    def.type = i == 1 ? joints::JointType::Hinge : joints::JointType::Ball;
    def.bodyA =
        i == 0 ? geometry::BodyId{} : geometry::BodyId{static_cast<std::uint32_t>(i - 1), 0};
    def.bodyB = {static_cast<std::uint32_t>(i), 0};
    const Eigen::Vector3d anchor(0.1 * i, 0.02 * i - 0.01 * (i > 0), 0.0);
    def.frameA.anchor = i == 0 ? anchor : Eigen::Vector3d(anchor - state.poses[i - 1].position);
    def.frameB.anchor = anchor - x;
    items.push_back(static_cast<std::int32_t>(stage.create(def).index));
  }
  std::vector<Eigen::Vector3d> u;
  for (const bool reversed : {false, true}) {
    std::vector<std::int32_t> order = items;
    if (reversed) std::reverse(order.begin(), order.end());
    ASSERT_TRUE(stage.boundaryVelocities(order, state, state.poses, state.linearVelocities,
                                         state.angularVelocities, u));
    for (std::size_t i = 0; i < 3; ++i)
      EXPECT_LT((u[i] - state.linearVelocities[i]).norm(), 1e-14) << i << " reversed " << reversed;
  }
  // The same chain cut from the world (its first joint removed) and moving rigidly with an extra
  // translation: a free island, started from its lowest body's own velocity.
  stage.remove({static_cast<std::uint32_t>(items[0]), 0});
  const Eigen::Vector3d drift(0.4, 0.0, -2.0);
  for (std::size_t i = 0; i < 3; ++i) state.linearVelocities[i] += drift;
  ASSERT_TRUE(stage.boundaryVelocities({items.begin() + 1, items.end()}, state, state.poses,
                                       state.linearVelocities, state.angularVelocities, u));
  for (std::size_t i = 0; i < 3; ++i)
    EXPECT_LT((u[i] - state.linearVelocities[i]).norm(), 1e-14) << i;
  // With the chain's own angular velocities changed, u follows the angular velocities, not the
  // bodies' linear ones (which no longer agree with the joints).
  state.angularVelocities[2] *= 2.0;
  ASSERT_TRUE(stage.boundaryVelocities({items.begin() + 1, items.end()}, state, state.poses,
                                       state.linearVelocities, state.angularVelocities, u));
  EXPECT_GT((u[2] - state.linearVelocities[2]).norm(), 1e-3);
  joints::JointDef slider;
  slider.type = joints::JointType::Prismatic;
  slider.bodyB = {0, 0};
  const std::int32_t prismatic = static_cast<std::int32_t>(stage.create(slider).index);
  const std::vector<std::int32_t> withSlider = {items[1], prismatic};
  EXPECT_FALSE(stage.boundaryVelocities(withSlider, state, state.poses, state.linearVelocities,
                                        state.angularVelocities, u));
}
