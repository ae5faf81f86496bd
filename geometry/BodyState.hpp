#pragma once
// The state of every body, in arrays (structure of arrays) indexed by BodyId::index. The body
// frame is the centre-of-mass frame: poses[i].position is the COM in world, velocities are the
// COM's linear velocity and the angular velocity, both in world coordinates.
// Integrators and the contact pipeline read and write these arrays; the World owns them.
#include <coulomb/geometry/Pose.hpp>

#include <cstdint>
#include <vector>

namespace coulomb::geometry {

enum class MotionType : std::uint8_t {
  Static,     // never moves; infinite mass
  Kinematic,  // moves with its prescribed velocities; infinite mass (pushes, is never pushed)
  Dynamic,    // moves under forces and impulses
};

const char* motionTypeName(MotionType type);

struct BodyState {
  std::vector<Pose> poses;                            // COM frame in world
  std::vector<Eigen::Vector3d> linearVelocities;      // [m/s] COM velocity, world
  std::vector<Eigen::Vector3d> angularVelocities;     // [rad/s] world
  std::vector<double> inverseMasses;                  // [1/kg]; 0 for static/kinematic
  std::vector<Eigen::Matrix3d> bodyInverseInertias;   // [1/(kg m^2)] about COM, body axes
  std::vector<Eigen::Matrix3d> worldInverseInertias;  // R I_body^-1 R^T, kept current
  // Principal decomposition of the body inertia, used by the rotation integrator:
  // I_body = P diag(principalMoments) P^T with P = principalFrames[i].
  std::vector<Eigen::Vector3d> principalMoments;    // [kg m^2]; 0 for static/kinematic
  std::vector<Eigen::Quaterniond> principalFrames;  // principal axes in the body frame
  std::vector<MotionType> motionTypes;
  std::vector<std::uint8_t> alive;       // 0 for a removed body's free slot
  std::vector<std::uint8_t> asleep;      // 1: a dynamic body put to sleep (engine/Sleep): at rest,
                                         // not integrated, not solved, like a static body
  std::vector<Eigen::Vector3d> forces;   // [N] at the COM, world; cleared every step
  std::vector<Eigen::Vector3d> torques;  // [N m] world; cleared every step

  [[nodiscard]] std::size_t size() const { return poses.size(); }
  [[nodiscard]] bool isDynamic(std::size_t i) const {
    return alive[i] != 0 && motionTypes[i] == MotionType::Dynamic && asleep[i] == 0;
  }
  /// A kinematic body with a non-zero velocity (it wakes the sleeping bodies it touches).
  [[nodiscard]] bool isMovingKinematic(std::size_t i) const {
    return alive[i] != 0 && motionTypes[i] == MotionType::Kinematic &&
           !(linearVelocities[i].isZero(0.0) && angularVelocities[i].isZero(0.0));
  }

  /// Appends a slot (or reuses slot `index` when index < size()) with the given values.
  /// For a dynamic body `mass` > 0 and `inertiaAboutCom` (body axes) is positive definite; for the
  /// other types both are ignored (infinite mass).
  void assign(std::size_t index, MotionType type, const Pose& pose,
              const Eigen::Vector3d& linearVelocity, const Eigen::Vector3d& angularVelocity,
              double mass, const Eigen::Matrix3d& inertiaAboutCom);
  /// Marks slot `index` free: static, at rest, no forces.
  void clear(std::size_t index);

  /// worldInverseInertias[i] = R bodyInverseInertias[i] R^T for the current orientation.
  void refreshWorldInertia(std::size_t i);
  /// World angular momentum I_world omega [kg m^2/s] of body i (zero for non-dynamic bodies).
  [[nodiscard]] Eigen::Vector3d angularMomentum(std::size_t i) const;
  /// Kinetic energy [J] of body i (zero for non-dynamic bodies).
  [[nodiscard]] double kineticEnergy(std::size_t i) const;
  void clearForces();
};

/// 64-bit FNV-1a hash of the bit patterns of every live body's pose and velocities (and slot
/// layout). Equal hashes across runs mean bit-identical states (determinism tests).
std::uint64_t stateHash(const BodyState& state);

}  // namespace coulomb::geometry
