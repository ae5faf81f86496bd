#pragma once
// The jointed scenes of docs/scene-specifications.md (A6 chain, B8 pendulum, B9 double pendulum,
// B10 four-bar) built through the C++ API, with the metrics those sections define. Numbers copied
// from docs/scene-specifications.md (tests never read the design folder).
#include <coulomb/engine/World.hpp>

#include <Eigen/Geometry>

#include <cmath>
#include <numbers>
#include <vector>

namespace coulomb::testing {

inline constexpr double kG = 9.81;

inline geometry::SpatialInertia principalInertia(double m, const Eigen::Vector3d& moments) {
  return {m, Eigen::Vector3d::Zero(), moments.asDiagonal()};
}

inline geometry::BodyId addBody(engine::World& world, const std::string& name,
                                const geometry::Pose& pose, double mass,
                                const Eigen::Vector3d& moments) {
  engine::BodyDesc desc;
  desc.name = name;
  desc.pose = pose;
  desc.mass = principalInertia(mass, moments);
  return world.createBody(desc);
}

/// A joint with parallel frames: anchors given, axis `axis` (normal any perpendicular).
inline engine::JointDesc jointDesc(joints::JointType type, geometry::BodyId a, geometry::BodyId b,
                                   const Eigen::Vector3d& anchorA, const Eigen::Vector3d& anchorB,
                                   const Eigen::Vector3d& axis = Eigen::Vector3d::UnitY(),
                                   const Eigen::Vector3d& normal = Eigen::Vector3d::UnitX()) {
  engine::JointDesc d;
  d.type = type;
  d.bodyA = a;
  d.bodyB = b;
  d.frameA.anchor = anchorA;
  d.frameB.anchor = anchorB;
  d.frameA.axis = d.frameB.axis = axis;
  d.frameA.normal = d.frameB.normal = normal;
  return d;
}

/// The world frame of a joint frame on a body whose local frame axes rotate by `r`.
inline engine::JointDesc rotatedFrames(engine::JointDesc d, const Eigen::Quaterniond& rotA,
                                       const Eigen::Quaterniond& rotB) {
  const Eigen::Vector3d axis = d.frameA.axis, normal = d.frameA.normal;
  d.frameA.axis = rotA.conjugate() * axis;
  d.frameA.normal = rotA.conjugate() * normal;
  d.frameB.axis = rotB.conjugate() * axis;
  d.frameB.normal = rotB.conjugate() * normal;
  return d;
}

/// Largest distance between the world anchors of every joint of the world.
inline double maxAnchorGap(const engine::World& world, const std::vector<geometry::JointId>& ids) {
  double gap = 0.0;
  for (const geometry::JointId id : ids) {
    const joints::JointDef& j = world.joint(id);
    const auto anchor = [&](geometry::BodyId b, const Eigen::Vector3d& local) {
      return b.valid() ? world.pose(b).apply(local) : local;
    };
    gap =
        std::max(gap, (anchor(j.bodyA, j.frameA.anchor) - anchor(j.bodyB, j.frameB.anchor)).norm());
  }
  return gap;
}

struct JointedScene {
  engine::World world;
  std::vector<geometry::BodyId> bodies;
  std::vector<geometry::JointId> joints;
  explicit JointedScene(engine::WorldSettings s) : world(std::move(s)) {}
};

/// docs/scene-specifications.md A6: N capsule links (0.1 kg, I =
/// (4.857143e-6, 7.557143e-5, 7.557143e-5)), ball joints 0.1 m apart, released horizontal along +x,
/// first anchor at the world origin.
inline void buildChain(JointedScene& scene, int links) {
  const Eigen::Vector3d moments(4.857143e-6, 7.557143e-5, 7.557143e-5);
  for (int i = 0; i < links; ++i) {
    scene.bodies.push_back(addBody(scene.world, "link" + std::to_string(i),
                                   geometry::Pose::translation({(i + 0.5) * 0.1, 0, 0}), 0.1,
                                   moments));
    const geometry::BodyId parent = i == 0 ? geometry::BodyId{} : scene.bodies[i - 1];
    const Eigen::Vector3d parentAnchor =
        i == 0 ? Eigen::Vector3d::Zero() : Eigen::Vector3d(0.05, 0, 0);
    scene.joints.push_back(scene.world.createJoint(
        jointDesc(joints::JointType::Ball, parent, scene.bodies[i], parentAnchor, {-0.05, 0, 0})));
  }
}

/// docs/scene-specifications.md B8: sphere bob 1 kg, I 0.001, at (1, 0, 0), ball joint at the
/// origin.
inline void buildPendulum(JointedScene& scene, joints::JointType type = joints::JointType::Ball) {
  scene.bodies.push_back(addBody(scene.world, "bob", geometry::Pose::translation({1, 0, 0}), 1.0,
                                 Eigen::Vector3d::Constant(0.001)));
  scene.joints.push_back(scene.world.createJoint(
      jointDesc(type, geometry::BodyId{}, scene.bodies[0], Eigen::Vector3d::Zero(), {-1, 0, 0})));
}

/// R_y(alpha) as a quaternion (docs/scene-specifications.md section 0).
inline Eigen::Quaterniond rotY(double alpha) {
  return Eigen::Quaterniond(Eigen::AngleAxisd(alpha, Eigen::Vector3d::UnitY()));
}

/// docs/scene-specifications.md B9: two capsules (1 kg, I = (1.978082e-4, 0.01985808, 0.01985808)),
/// hinges about world y, angles theta_i from the downward vertical.
inline void buildDoublePendulum(JointedScene& scene, double theta1, double theta2) {
  const Eigen::Vector3d moments(1.978082e-4, 0.01985808, 0.01985808);
  const Eigen::Vector3d d1(std::sin(theta1), 0, -std::cos(theta1));
  const Eigen::Vector3d d2(std::sin(theta2), 0, -std::cos(theta2));
  const Eigen::Quaterniond r1 = rotY(std::numbers::pi / 2 - theta1);
  const Eigen::Quaterniond r2 = rotY(std::numbers::pi / 2 - theta2);
  scene.bodies.push_back(addBody(scene.world, "link1", {r1, 0.25 * d1}, 1.0, moments));
  scene.bodies.push_back(addBody(scene.world, "link2", {r2, 0.5 * d1 + 0.25 * d2}, 1.0, moments));
  using joints::JointType;
  scene.joints.push_back(scene.world.createJoint(rotatedFrames(
      jointDesc(JointType::Hinge, {}, scene.bodies[0], Eigen::Vector3d::Zero(), {-0.25, 0, 0}),
      Eigen::Quaterniond::Identity(), r1)));
  scene.joints.push_back(scene.world.createJoint(rotatedFrames(
      jointDesc(JointType::Hinge, scene.bodies[0], scene.bodies[1], {0.25, 0, 0}, {-0.25, 0, 0}),
      r1, r2)));
}

}  // namespace coulomb::testing
