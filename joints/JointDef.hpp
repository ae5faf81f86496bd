#pragma once
// What defines a joint between two bodies (or a body and the world): its type, a frame on each
// body, and the optional limit, motor, friction, breaking threshold and stabilization policy.
//
// Frames: each body carries a JointFrame (anchor point, unit `axis`, unit `normal` perpendicular
// to it; binormal = axis x normal) in that body's centre-of-mass frame (the world frame when the
// body is the world). The joint keeps the two frames related as its type says:
//   Ball       anchors coincide (3 rows)
//   Hinge      anchors coincide, axes aligned (5 rows); coordinate = angle of normal_B about axis_A
//   Prismatic  axes and orientations aligned, anchor B on the line of axis A (5 rows);
//              coordinate = displacement of anchor B along axis A
//   Fixed      anchors and orientations coincide (6 rows)
//   Universal  anchors coincide, axis_A perpendicular to normal_B (4 rows): the cross of a
//              Cardan joint has arms axis_A (on A) and normal_B (on B)
// Limits, motors and friction act on the coordinate, so they exist for Hinge and Prismatic only.
#include <coulomb/geometry/Ids.hpp>
#include <coulomb/joints/Stabilization.hpp>

#include <Eigen/Core>

#include <cstdint>
#include <limits>
#include <optional>
#include <string>

namespace coulomb::joints {

enum class JointType : std::uint8_t { Ball, Hinge, Prismatic, Fixed, Universal };

const char* jointTypeName(JointType type);
std::optional<JointType> jointTypeFromName(const std::string& name);
/// Equality rows of the type (3, 5, 5, 6, 4).
int equalityRowCount(JointType type);
/// True for the types with a scalar coordinate (hinge angle, prismatic displacement).
bool hasCoordinate(JointType type);

struct JointFrame {
  Eigen::Vector3d anchor = Eigen::Vector3d::Zero();   // [m] in the body's COM frame
  Eigen::Vector3d axis = Eigen::Vector3d::UnitX();    // unit
  Eigen::Vector3d normal = Eigen::Vector3d::UnitY();  // unit, perpendicular to axis
  [[nodiscard]] Eigen::Vector3d binormal() const { return axis.cross(normal); }
};

/// Keeps the coordinate in [lower, upper] (unilateral rows). [rad] for hinges, [m] for sliders.
struct JointLimit {
  bool enabled = false;
  double lower = 0.0;
  double upper = 0.0;
  /// [-] Newton restitution at the stop (0 = the swing stops dead, 1 = it bounces back).
  double restitution = 0.0;
};

/// Drives the coordinate's rate to `targetVelocity` [rad/s or m/s] with at most `maxForce`
/// [N m or N] (a bounded row, |lambda| <= maxForce h).
struct JointMotor {
  bool enabled = false;
  double targetVelocity = 0.0;
  double maxForce = 0.0;
};

struct JointDef {
  std::string name;  // optional; used in messages
  JointType type = JointType::Ball;
  geometry::BodyId bodyA;  // invalid id = the world
  geometry::BodyId bodyB;  // invalid id = the world
  JointFrame frameA;
  JointFrame frameB;
  JointLimit limit;
  JointMotor motor;
  /// [N m or N] Dry joint friction on the coordinate: a bounded row |lambda| <= friction h that
  /// holds the joint still below this load. 0 = none. Not combined with a motor (a motor with
  /// target 0 is friction).
  double friction = 0.0;
  /// [N] / [N m] The joint breaks (stops acting, reported once) when its reaction force on B
  /// or torque about the anchor exceeds these. Default: unbreakable.
  double breakForce = std::numeric_limits<double>::infinity();
  double breakTorque = std::numeric_limits<double>::infinity();
  /// This joint's policy; nullopt = the world's (WorldSettings::jointStabilization).
  std::optional<Stabilization> stabilization;
  std::uint64_t userData = 0;  // the user's value (World::joint(id).userData); never read
};

/// nullopt if `def` is usable, else a message naming the first bad value, e.g. "joint 'knee':
/// frameA.axis must have unit length (got 1.2)". Checks: frames finite, axes unit (1e-6) and
/// perpendicular, a joint from a body to itself, two world ends, limits ordered, motor/friction
/// bounds >= 0, limit/motor/friction on a type without a coordinate, break thresholds > 0.
std::optional<std::string> validateJointDef(const JointDef& def);

}  // namespace coulomb::joints
