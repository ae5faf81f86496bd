#include <coulomb/io/JointJson.hpp>

#include <Eigen/Geometry>

#include <cmath>
#include <string>

namespace coulomb::engine::io {
namespace {

using joints::JointFrame;
using joints::JointType;

constexpr double kUnitTolerance = 1e-6;  // as validateJointDef

double nonNegative(const JsonNode& node) {
  const double value = node.number();
  if (value < 0.0) node.fail("must be >= 0");
  return value;
}

Eigen::Vector3d unitVector(const JsonNode& node) {
  const Eigen::Vector3d v = node.vector3();
  if (v.norm() < 1e-12) node.fail("must be non-zero");
  return v.normalized();
}

/// A deterministic unit vector perpendicular to `axis` (for a frame whose normal is not given).
Eigen::Vector3d anyPerpendicular(const Eigen::Vector3d& axis) {
  Eigen::Index least = 0;
  axis.cwiseAbs().minCoeff(&least);
  return axis.cross(Eigen::Vector3d::Unit(least)).normalized();
}

/// {"anchor", "axis", "normal"} in some frame; the normal defaults to a perpendicular of the axis.
JointFrame parseFrame(const JsonNode& node, const char* anchorKey, const char* axisKey,
                      const char* normalKey) {
  JointFrame frame;
  frame.anchor = node.vector3(anchorKey, Eigen::Vector3d::Zero());
  if (node.has(axisKey)) frame.axis = unitVector(node.child(axisKey));
  if (node.has(normalKey)) {
    frame.normal = unitVector(node.child(normalKey));
    if (std::abs(frame.normal.dot(frame.axis)) > kUnitTolerance)
      node.child(normalKey).fail("must be perpendicular to \"" + std::string(axisKey) + "\"");
  } else {
    frame.normal = anyPerpendicular(frame.axis);
  }
  return frame;
}

/// A frame given in world coordinates, in the reference frame of a body at `pose`.
JointFrame toBodyFrame(const JointFrame& world, const geometry::Pose& pose) {
  const Eigen::Quaterniond inverse = pose.rotation.conjugate();
  JointFrame local;
  local.anchor = inverse * (world.anchor - pose.position);
  local.axis = inverse * world.axis;
  local.normal = inverse * world.normal;
  return local;
}

/// Index of the body named by `node` in `bodies` (-1 = "world").
int bodyIndex(const JsonNode& node, const std::vector<BodyDesc>& bodies) {
  const std::string name = node.string();
  if (name == "world") return -1;
  int found = -1;
  std::vector<std::string> names;
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    names.push_back(bodies[i].name);
    if (bodies[i].name != name) continue;
    if (found >= 0) node.fail("body name '" + name + "' is not unique");
    found = static_cast<int>(i);
  }
  if (found < 0) {
    std::string message = "unknown body '" + name + "'";
    if (auto s = nearestName(name, names)) message += "; did you mean '" + *s + "'?";
    node.fail(message + " (bodies are named by their \"name\"; \"world\" is the world)");
  }
  return found;
}

JointType parseJointType(const JsonNode& node) {
  const std::string type = node.string();
  if (auto t = joints::jointTypeFromName(type)) return *t;
  std::string message = "unknown joint type '" + type + "'";
  if (auto s = nearestName(type, {"ball", "hinge", "prismatic", "fixed", "universal"}))
    message += "; did you mean '" + *s + "'?";
  node.fail(message + " (ball, hinge, prismatic, fixed or universal)");
}

void parseLimit(const JsonNode& node, joints::JointLimit& limit) {
  node.allowOnly({"lower", "upper", "restitution"});
  limit.enabled = true;
  limit.lower = node.child("lower").number();
  limit.upper = node.child("upper").number();
  if (limit.lower > limit.upper) node.child("upper").fail("must be >= \"lower\"");
  limit.restitution = node.number("restitution", 0.0);
  if (limit.restitution < 0.0 || limit.restitution > 1.0)
    node.child("restitution").fail("must be in [0, 1]");
}

void parseMotor(const JsonNode& node, joints::JointMotor& motor) {
  node.allowOnly({"target_velocity", "max_force", "max_torque"});
  motor.enabled = true;
  motor.targetVelocity = node.number("target_velocity", 0.0);
  if (node.has("max_force") == node.has("max_torque"))
    node.fail("give one of \"max_force\" [N] (prismatic) or \"max_torque\" [N m] (hinge)");
  motor.maxForce = nonNegative(node.child(node.has("max_force") ? "max_force" : "max_torque"));
}

}  // namespace

joints::Stabilization parseStabilization(const JsonNode& node, joints::Stabilization base) {
  const auto method = [&](const JsonNode& m) {
    const std::string name = m.string();
    if (auto found = joints::stabilizationMethodFromName(name)) return *found;
    std::string message = "unknown stabilization '" + name + "'";
    if (auto s = nearestName(name, {"baumgarte", "predicted_state", "none"}))
      message += "; did you mean '" + *s + "'?";
    m.fail(message + " (baumgarte, predicted_state or none)");
  };
  if (node.raw().is_string()) {
    base.method = method(node);
    return base;
  }
  node.allowOnly({"method", "beta", "slop", "iterations", "tolerance", "energy"});
  if (node.has("method")) base.method = method(node.child("method"));
  if (node.has("beta")) {
    base.baumgarte.beta = node.child("beta").number();
    if (base.baumgarte.beta < 0.0 || base.baumgarte.beta > 1.0)
      node.child("beta").fail("must be in [0, 1]");
  }
  if (node.has("slop")) base.baumgarte.slop = nonNegative(node.child("slop"));
  if (node.has("iterations")) {
    const std::uint64_t n = node.child("iterations").unsignedInteger();
    if (n < 1 || n > 10000) node.child("iterations").fail("must be in [1, 10000]");
    base.predictedState.iterations = static_cast<int>(n);
  }
  if (node.has("tolerance"))
    base.predictedState.tolerance = node.child("tolerance").positiveNumber();
  if (node.has("energy")) {
    const JsonNode& energy = node.child("energy");
    const std::string name = energy.string();
    const auto target = joints::energyTargetFromName(name);
    if (!target) {
      std::string message = "unknown energy target '" + name + "'";
      if (auto s = nearestName(name, {"none", "modified", "exact"}))
        message += "; did you mean '" + *s + "'?";
      energy.fail(message + " (none, modified or exact)");
    }
    base.predictedState.energy = *target;
  }
  return base;
}

SceneJoint parseJoint(const JsonNode& node, const std::vector<BodyDesc>& bodies,
                      const joints::Stabilization& worldPolicy) {
  node.allowOnly({"name", "type", "body_a", "body_b", "anchor", "axis", "normal", "frame_a",
                  "frame_b", "limit", "motor", "friction", "break_force", "break_torque",
                  "stabilization"});
  SceneJoint joint;
  joints::JointDef& def = joint.def;
  def.name = node.string("name", "");
  def.type = parseJointType(node.child("type"));
  joint.bodyA = node.has("body_a") ? bodyIndex(node.child("body_a"), bodies) : -1;
  joint.bodyB = node.has("body_b") ? bodyIndex(node.child("body_b"), bodies) : -1;
  if (joint.bodyA < 0 && joint.bodyB < 0)
    node.fail("at least one of body_a, body_b must be a body");
  if (joint.bodyA == joint.bodyB) node.child("body_b").fail("a joint needs two different bodies");

  const bool worldForm = node.has("anchor") || node.has("axis") || node.has("normal");
  const bool bodyForm = node.has("frame_a") || node.has("frame_b");
  if (worldForm && bodyForm)
    node.fail(
        "give the frame either in world coordinates (\"anchor\", \"axis\", \"normal\") or "
        "per body (\"frame_a\", \"frame_b\"), not both");
  const bool needsAxis = def.type == JointType::Hinge || def.type == JointType::Prismatic ||
                         def.type == JointType::Universal;
  if (bodyForm) {
    for (const char* key : {"frame_a", "frame_b"}) {
      if (!node.has(key))
        node.fail(std::string("\"") + key + "\" is missing (frames come in pairs)");
      const JsonNode f = node.child(key);
      f.allowOnly({"anchor", "axis", "normal"});
      if (needsAxis && !f.has("axis"))
        f.fail("\"axis\" is required for a " + node.string("type", ""));
    }
    def.frameA = parseFrame(node.child("frame_a"), "anchor", "axis", "normal");
    def.frameB = parseFrame(node.child("frame_b"), "anchor", "axis", "normal");
  } else {
    if (!node.has("anchor"))
      node.fail("\"anchor\" (world coordinates) or \"frame_a\"/\"frame_b\" is required");
    if (needsAxis && !node.has("axis"))
      node.fail("\"axis\" is required for a " + node.string("type", ""));
    const JointFrame world = parseFrame(node, "anchor", "axis", "normal");
    const auto local = [&](int body) {
      return body < 0 ? world : toBodyFrame(world, bodies[static_cast<std::size_t>(body)].pose);
    };
    def.frameA = local(joint.bodyA);
    def.frameB = local(joint.bodyB);
  }

  const bool coordinate = joints::hasCoordinate(def.type);
  for (const char* key : {"limit", "motor", "friction"})
    if (node.has(key) && !coordinate)
      node.child(key).fail("only hinge and prismatic joints have a limit, motor or friction");
  if (node.has("limit")) parseLimit(node.child("limit"), def.limit);
  if (node.has("motor")) parseMotor(node.child("motor"), def.motor);
  if (node.has("friction")) def.friction = nonNegative(node.child("friction"));
  if (node.has("break_force")) def.breakForce = node.child("break_force").positiveNumber();
  if (node.has("break_torque")) def.breakTorque = node.child("break_torque").positiveNumber();
  if (node.has("stabilization"))
    def.stabilization = parseStabilization(node.child("stabilization"), worldPolicy);
  return joint;
}

joints::JointDef parseLiveJoint(std::string_view text, const World& world,
                                const std::string& source) {
  nlohmann::json document;
  try {
    document = nlohmann::json::parse(text.begin(), text.end());
  } catch (const nlohmann::json::exception& e) {
    throw CoulombError(source + ": invalid JSON: " + e.what());
  }
  // The live bodies as the scene parser knows bodies: names and reference-frame poses (the
  // World keeps COM frames; the reference frame sits -R c from the COM, same axes).
  std::vector<BodyDesc> bodies;
  std::vector<geometry::BodyId> ids;
  const geometry::BodyState& state = world.state();
  for (std::size_t slot = 0; slot < state.size(); ++slot) {
    if (!state.alive[slot]) continue;
    const geometry::BodyId id = world.idAt(slot);
    BodyDesc body;
    body.name = world.name(id);
    body.pose = state.poses[slot];
    body.pose.position -= body.pose.rotation * world.massProperties(id).centerOfMass;
    bodies.push_back(std::move(body));
    ids.push_back(id);
  }
  const SceneJoint joint =
      parseJoint(JsonNode(document, source, "joint"), bodies, world.settings().jointStabilization);
  joints::JointDef def = joint.def;
  def.bodyA = joint.bodyA < 0 ? geometry::BodyId{} : ids[static_cast<std::size_t>(joint.bodyA)];
  def.bodyB = joint.bodyB < 0 ? geometry::BodyId{} : ids[static_cast<std::size_t>(joint.bodyB)];
  return def;
}

}  // namespace coulomb::engine::io
