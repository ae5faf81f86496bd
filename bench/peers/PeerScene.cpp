#include "PeerScene.hpp"

#include "scenes/SceneRegistry.hpp"

#include <coulomb/engine/CoulombError.hpp>

#include <cmath>
#include <variant>

namespace coulomb::peers {
namespace {

[[noreturn]] void unsupported(const engine::io::Scene& scene, const std::string& where,
                              const std::string& what) {
  throw engine::CoulombError(scene.source + ": " + where + ": " + what +
                             " (not modelled by the peer adapters)");
}

PeerShape convertShape(const engine::io::Scene& scene, const std::string& where,
                       const engine::BodyDesc& body, const engine::ShapeDesc& desc) {
  if (desc.localPose.position.norm() != 0.0) unsupported(scene, where, "shape offset from the COM");
  PeerShape shape;
  shape.collides = desc.filter.category != 0 && desc.filter.mask != 0;
  if (const auto* box = std::get_if<geometry::Box>(&desc.shape)) {
    if (!desc.localPose.rotation.isApprox(Eigen::Quaterniond::Identity(), 1e-15))
      unsupported(scene, where, "rotated box");
    shape.kind = PeerShape::Kind::Box;
    shape.halfExtents = box->halfExtents;
  } else if (const auto* sphere = std::get_if<geometry::Sphere>(&desc.shape)) {
    shape.kind = PeerShape::Kind::Sphere;
    shape.radius = sphere->radius;
  } else if (const auto* capsule = std::get_if<geometry::Capsule>(&desc.shape)) {
    shape.kind = PeerShape::Kind::Capsule;
    shape.radius = capsule->radius;
    shape.halfLength = capsule->halfLength;
    shape.capsuleAxis = desc.localPose.rotation * Eigen::Vector3d::UnitZ();
  } else if (const auto* plane = std::get_if<geometry::Plane>(&desc.shape)) {
    const Eigen::Quaterniond toWorld = body.pose.rotation * desc.localPose.rotation;
    shape.kind = PeerShape::Kind::Plane;
    shape.planeNormal = toWorld * plane->normal.normalized();
    shape.planeOffset = plane->offset + shape.planeNormal.dot(body.pose.position);
  } else {
    unsupported(scene, where, std::string("shape '") + geometry::shapeKindName(desc.shape) + "'");
  }
  return shape;
}

}  // namespace

PeerScene loadPeerScene(std::string_view name) {
  PeerScene out;
  out.source = scenes::loadBuiltinScene(name);
  const engine::io::Scene& scene = out.source;
  out.name = std::string(name);
  out.gravity = scene.settings.gravity;
  out.dt = scene.settings.timeStep;
  out.steps = scene.steps;
  if (!scene.articulations.empty()) unsupported(scene, "articulations", "reduced coordinates");
  for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
    const engine::BodyDesc& desc = scene.bodies[i];
    const std::string where = "bodies[" + std::to_string(i) + "] '" + desc.name + "'";
    if (desc.shapes.size() != 1) unsupported(scene, where, "not exactly one shape");
    PeerBody body;
    body.name = desc.name;
    body.isStatic = desc.motionType == geometry::MotionType::Static;
    if (desc.motionType == geometry::MotionType::Kinematic) unsupported(scene, where, "kinematic");
    body.position = desc.pose.position;
    body.rotation = desc.pose.rotation;
    body.linearVelocity = desc.linearVelocity;
    body.angularVelocity = desc.angularVelocity;
    if (!body.isStatic) {
      // docs/benchmarks.md "Peers in the same run": inertia is set explicitly, never recomputed
      // from the shape.
      if (!desc.mass) unsupported(scene, where, "no explicit mass and inertia");
      const geometry::SpatialInertia& m = *desc.mass;
      if (m.centerOfMass.norm() != 0.0) unsupported(scene, where, "COM offset");
      if (!m.inertiaAboutCom.isDiagonal(0.0)) unsupported(scene, where, "non-principal axes");
      body.mass = m.mass;
      body.inertia = m.inertiaAboutCom.diagonal();
    }
    body.shape = convertShape(scene, where, desc, desc.shapes.front());
    body.friction = desc.shapes.front().material.friction;
    body.restitution = desc.shapes.front().material.restitution;
    out.bodies.push_back(body);
  }
  for (std::size_t k = 0; k < scene.joints.size(); ++k) {
    const engine::io::SceneJoint& joint = scene.joints[k];
    if (joint.def.type != joints::JointType::Ball)
      unsupported(scene, "joints[" + std::to_string(k) + "]", "joint type other than ball");
    out.joints.push_back(
        {joint.bodyA, joint.bodyB, joint.def.frameA.anchor, joint.def.frameB.anchor});
  }
  return out;
}

}  // namespace coulomb::peers
