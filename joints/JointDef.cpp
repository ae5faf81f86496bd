#include <coulomb/joints/JointDef.hpp>

#include <cmath>
#include <sstream>

namespace coulomb::joints {
namespace {

constexpr double kUnitTolerance = 1e-6;

std::optional<std::string> checkFrame(const JointFrame& f, const char* side) {
  std::ostringstream out;
  if (!f.anchor.allFinite() || !f.axis.allFinite() || !f.normal.allFinite()) {
    out << side << " must be finite (anchor " << f.anchor.transpose() << ", axis "
        << f.axis.transpose() << ", normal " << f.normal.transpose() << ")";
  } else if (std::abs(f.axis.norm() - 1.0) > kUnitTolerance) {
    out << side << ".axis must have unit length (got " << f.axis.norm() << ")";
  } else if (std::abs(f.normal.norm() - 1.0) > kUnitTolerance) {
    out << side << ".normal must have unit length (got " << f.normal.norm() << ")";
  } else if (std::abs(f.axis.dot(f.normal)) > kUnitTolerance) {
    out << side
        << ".normal must be perpendicular to the axis (axis . normal = " << f.axis.dot(f.normal)
        << ")";
  } else {
    return std::nullopt;
  }
  return out.str();
}

}  // namespace

const char* jointTypeName(JointType type) {
  switch (type) {
    case JointType::Ball:
      return "ball";
    case JointType::Hinge:
      return "hinge";
    case JointType::Prismatic:
      return "prismatic";
    case JointType::Fixed:
      return "fixed";
    case JointType::Universal:
      return "universal";
  }
  return "?";
}

std::optional<JointType> jointTypeFromName(const std::string& name) {
  for (auto t : {JointType::Ball, JointType::Hinge, JointType::Prismatic, JointType::Fixed,
                 JointType::Universal})
    if (name == jointTypeName(t)) return t;
  return std::nullopt;
}

int equalityRowCount(JointType type) {
  switch (type) {
    case JointType::Ball:
      return 3;
    case JointType::Hinge:
    case JointType::Prismatic:
      return 5;
    case JointType::Fixed:
      return 6;
    case JointType::Universal:
      return 4;
  }
  return 0;
}

bool hasCoordinate(JointType type) {
  return type == JointType::Hinge || type == JointType::Prismatic;
}

std::optional<std::string> validateJointDef(const JointDef& def) {
  const std::string who = "joint '" + def.name + "' (" + jointTypeName(def.type) + "): ";
  if (!def.bodyA.valid() && !def.bodyB.valid()) return who + "both ends are the world";
  if (def.bodyA.valid() && def.bodyA == def.bodyB)
    return who + "joins a body to itself (bodyA == bodyB)";
  if (auto bad = checkFrame(def.frameA, "frameA")) return who + *bad;
  if (auto bad = checkFrame(def.frameB, "frameB")) return who + *bad;
  const bool usesCoordinate = def.limit.enabled || def.motor.enabled || def.friction != 0.0;
  if (usesCoordinate && !hasCoordinate(def.type))
    return who + "limits, motors and friction need a hinge or prismatic joint";
  std::ostringstream out;
  if (def.limit.enabled && !(std::isfinite(def.limit.lower) && std::isfinite(def.limit.upper) &&
                             def.limit.lower <= def.limit.upper))
    out << "limit needs finite lower <= upper (got " << def.limit.lower << ", " << def.limit.upper
        << ")";
  else if (def.limit.enabled && !(def.limit.restitution >= 0.0 && def.limit.restitution <= 1.0))
    out << "limit restitution must be in [0, 1] (got " << def.limit.restitution << ")";
  else if (def.motor.enabled &&
           !(std::isfinite(def.motor.targetVelocity) && def.motor.maxForce >= 0.0))
    out << "motor needs a finite target velocity and max force >= 0 (got "
        << def.motor.targetVelocity << ", " << def.motor.maxForce << ")";
  else if (!(def.friction >= 0.0) || std::isinf(def.friction))
    out << "friction must be finite and >= 0 (got " << def.friction << ")";
  else if (def.motor.enabled && def.friction > 0.0)
    out << "has both a motor and friction (a motor with target 0 is friction)";
  else if (!(def.breakForce > 0.0) || !(def.breakTorque > 0.0))
    out << "break force and torque must be > 0 (got " << def.breakForce << ", " << def.breakTorque
        << ")";
  else if (def.stabilization)
    if (auto bad = def.stabilization->validate()) out << *bad;
  if (!out.str().empty()) return who + out.str();
  return std::nullopt;
}

}  // namespace coulomb::joints
