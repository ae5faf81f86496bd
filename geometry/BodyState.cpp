#include <coulomb/geometry/BodyState.hpp>
#include <coulomb/geometry/SpatialInertia.hpp>

#include <cstring>

namespace coulomb::geometry {

const char* motionTypeName(MotionType type) {
  switch (type) {
    case MotionType::Static:
      return "static";
    case MotionType::Kinematic:
      return "kinematic";
    case MotionType::Dynamic:
      return "dynamic";
  }
  return "unknown";
}

void BodyState::assign(std::size_t index, MotionType type, const Pose& pose,
                       const Eigen::Vector3d& linearVelocity,
                       const Eigen::Vector3d& angularVelocity, double mass,
                       const Eigen::Matrix3d& inertiaAboutCom) {
  if (index >= size()) {
    const std::size_t n = index + 1;
    poses.resize(n);
    linearVelocities.resize(n, Eigen::Vector3d::Zero());
    angularVelocities.resize(n, Eigen::Vector3d::Zero());
    inverseMasses.resize(n, 0.0);
    bodyInverseInertias.resize(n, Eigen::Matrix3d::Zero());
    worldInverseInertias.resize(n, Eigen::Matrix3d::Zero());
    principalMoments.resize(n, Eigen::Vector3d::Zero());
    principalFrames.resize(n, Eigen::Quaterniond::Identity());
    motionTypes.resize(n, MotionType::Static);
    alive.resize(n, 0);
    asleep.resize(n, 0);
    forces.resize(n, Eigen::Vector3d::Zero());
    torques.resize(n, Eigen::Vector3d::Zero());
  }
  Pose normalised = pose;
  normalised.rotation.normalize();
  poses[index] = normalised;
  motionTypes[index] = type;
  alive[index] = 1;
  asleep[index] = 0;
  forces[index].setZero();
  torques[index].setZero();
  const bool dynamic = type == MotionType::Dynamic;
  linearVelocities[index] = type == MotionType::Static ? Eigen::Vector3d::Zero() : linearVelocity;
  angularVelocities[index] = type == MotionType::Static ? Eigen::Vector3d::Zero() : angularVelocity;
  inverseMasses[index] = dynamic ? 1.0 / mass : 0.0;
  if (dynamic) {
    const PrincipalAxes axes = principalAxes(inertiaAboutCom);
    principalMoments[index] = axes.moments;
    principalFrames[index] = axes.rotation;
    const Eigen::Matrix3d p = axes.rotation.toRotationMatrix();
    bodyInverseInertias[index] = p * axes.moments.cwiseInverse().asDiagonal() * p.transpose();
  } else {
    principalMoments[index].setZero();
    principalFrames[index].setIdentity();
    bodyInverseInertias[index].setZero();
  }
  refreshWorldInertia(index);
}

void BodyState::clear(std::size_t index) {
  assign(index, MotionType::Static, Pose{}, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(), 0.0,
         Eigen::Matrix3d::Zero());
  alive[index] = 0;
}

void BodyState::refreshWorldInertia(std::size_t i) {
  const Eigen::Matrix3d r = poses[i].rotationMatrix();
  worldInverseInertias[i] = r * bodyInverseInertias[i] * r.transpose();
}

Eigen::Vector3d BodyState::angularMomentum(std::size_t i) const {
  if (!isDynamic(i)) return Eigen::Vector3d::Zero();
  // L = R P diag(I) P^T R^T omega, using the principal decomposition (no matrix inverse).
  const Eigen::Quaterniond toPrincipal = poses[i].rotation * principalFrames[i];
  const Eigen::Vector3d omegaPrincipal = toPrincipal.conjugate() * angularVelocities[i];
  return toPrincipal * principalMoments[i].cwiseProduct(omegaPrincipal).eval();
}

double BodyState::kineticEnergy(std::size_t i) const {
  if (!isDynamic(i)) return 0.0;
  const double translational = 0.5 * linearVelocities[i].squaredNorm() / inverseMasses[i];
  return translational + 0.5 * angularVelocities[i].dot(angularMomentum(i));
}

void BodyState::clearForces() {
  for (auto& f : forces) f.setZero();
  for (auto& t : torques) t.setZero();
}

namespace {
struct Fnv1a {
  std::uint64_t value = 1469598103934665603ull;
  void bytes(const void* data, std::size_t n) {
    const auto* p = static_cast<const unsigned char*>(data);
    for (std::size_t k = 0; k < n; ++k) value = (value ^ p[k]) * 1099511628211ull;
  }
  void doubles(const double* data, std::size_t n) { bytes(data, n * sizeof(double)); }
};
}  // namespace

std::uint64_t stateHash(const BodyState& state) {
  Fnv1a hash;
  for (std::size_t i = 0; i < state.size(); ++i) {
    if (state.alive[i] == 0) continue;
    const std::uint64_t slot = i;
    hash.bytes(&slot, sizeof slot);
    hash.doubles(state.poses[i].rotation.coeffs().data(), 4);
    hash.doubles(state.poses[i].position.data(), 3);
    hash.doubles(state.linearVelocities[i].data(), 3);
    hash.doubles(state.angularVelocities[i].data(), 3);
  }
  return hash.value;
}

}  // namespace coulomb::geometry
