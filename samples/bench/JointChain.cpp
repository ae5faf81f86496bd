#include "JointChain.hpp"

#include <algorithm>

namespace coulomb::samples {

namespace {
constexpr double kLinkMass = 0.1;    // [kg]
constexpr double kLinkLength = 0.1;  // [m]
constexpr double kGravity = 9.81;    // [m/s^2]
}  // namespace

BallChain buildBallChain(int links, double timeStep, const std::string& solver,
                         joints::StabilizationMethod policy, joints::EnergyTarget energy) {
  engine::WorldSettings settings;
  settings.timeStep = timeStep;
  settings.solve.choice = coulomb::solvers::solverChoice(solver);
  settings.jointStabilization.method = policy;
  settings.jointStabilization.predictedState.energy = energy;
  BallChain chain{engine::World(settings), {}};
  geometry::BodyId parent;
  for (int i = 0; i < links; ++i) {
    engine::BodyDesc link;
    link.name = "link" + std::to_string(i);
    link.pose = geometry::Pose::translation({(i + 0.5) * kLinkLength, 0, 0});
    // Capsule r 0.01 m, length 0.1 m (docs/scene-specifications.md A6): principal inertia about the
    // COM.
    link.mass = {kLinkMass, Eigen::Vector3d::Zero(),
                 Eigen::Vector3d(4.857143e-6, 7.557143e-5, 7.557143e-5).asDiagonal()};
    const geometry::BodyId body = chain.world.createBody(link);
    engine::JointDesc joint;
    joint.type = joints::JointType::Ball;
    joint.bodyA = parent;
    joint.bodyB = body;
    joint.frameA.anchor =
        i == 0 ? Eigen::Vector3d::Zero() : Eigen::Vector3d(0.5 * kLinkLength, 0, 0);
    joint.frameB.anchor = Eigen::Vector3d(-0.5 * kLinkLength, 0, 0);
    chain.joints.push_back(chain.world.createJoint(joint));
    parent = body;
  }
  return chain;
}

double maxAnchorGap(const BallChain& chain) {
  double gap = 0.0;
  for (const geometry::JointId id : chain.joints) {
    const joints::JointDef& j = chain.world.joint(id);
    const auto anchor = [&](geometry::BodyId b, const Eigen::Vector3d& local) {
      return b.valid() ? chain.world.pose(b).apply(local) : local;
    };
    gap =
        std::max(gap, (anchor(j.bodyA, j.frameA.anchor) - anchor(j.bodyB, j.frameB.anchor)).norm());
  }
  return gap;
}

double chainReleasedEnergy(int links) {
  return kLinkMass * kGravity * kLinkLength * links * links / 2.0;
}

}  // namespace coulomb::samples
