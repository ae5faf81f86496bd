#include <coulomb/engine/Quarantine.hpp>

#include <cmath>
#include <sstream>

namespace coulomb::engine {

std::optional<std::string> QuarantineSettings::validate() const {
  std::ostringstream out;
  if (!(maxPosition > 0.0))
    out << "quarantine max position must be > 0 m (got " << maxPosition << ")";
  else if (!(maxLinearSpeed > 0.0))
    out << "quarantine max linear speed must be > 0 m/s (got " << maxLinearSpeed << ")";
  else if (!(maxAngularSpeed > 0.0))
    out << "quarantine max angular speed must be > 0 rad/s (got " << maxAngularSpeed << ")";
  else
    return std::nullopt;
  return out.str();
}

void Quarantine::begin(const geometry::BodyState& state, const ArticulationStage& trees) {
  flags_.resize(state.size(), 0);
  startPoses_ = state.poses;
  startQ_.resize(trees.slots());
  for (std::size_t k = 0; k < trees.slots(); ++k)
    if (const geometry::ArticulationId id = trees.idAt(k); id.valid()) startQ_[k] = trees.q(id);
}

std::optional<std::string> Quarantine::check(std::size_t i, const geometry::BodyState& state,
                                             const QuarantineSettings& limits) const {
  const geometry::Pose& pose = state.poses[i];
  const Eigen::Vector3d& v = state.linearVelocities[i];
  const Eigen::Vector3d& w = state.angularVelocities[i];
  // Nothing to report (every body, twice a step): no stream built. First without square roots:
  // a squared norm finite and below max^2 (1 - 1e-9) has its norm, correctly rounded, within max
  // (and a finite squared norm has finite entries); near a limit or not finite, the exact test.
  auto clearlyWithin = [](double squared, double max) {
    return max >= 0.0 && squared < max * max * (1.0 - 1e-9);
  };
  if (std::isfinite(pose.rotation.coeffs().squaredNorm()) &&
      clearlyWithin(pose.position.squaredNorm(), limits.maxPosition) &&
      clearlyWithin(v.squaredNorm(), limits.maxLinearSpeed) &&
      clearlyWithin(w.squaredNorm(), limits.maxAngularSpeed))
    return std::nullopt;
  if (pose.allFinite() && v.allFinite() && w.allFinite() &&
      !(pose.position.norm() > limits.maxPosition) && !(v.norm() > limits.maxLinearSpeed) &&
      !(w.norm() > limits.maxAngularSpeed))
    return std::nullopt;
  std::ostringstream why;
  if (!pose.allFinite())
    why << "non-finite pose";
  else if (!v.allFinite() || !w.allFinite())
    why << "non-finite velocity";
  else if (pose.position.norm() > limits.maxPosition)
    why << "position " << pose.position.norm() << " m beyond the limit " << limits.maxPosition
        << " m";
  else if (v.norm() > limits.maxLinearSpeed)
    why << "speed " << v.norm() << " m/s beyond the limit " << limits.maxLinearSpeed << " m/s";
  else if (w.norm() > limits.maxAngularSpeed)
    why << "angular speed " << w.norm() << " rad/s beyond the limit " << limits.maxAngularSpeed
        << " rad/s";
  else
    return std::nullopt;
  return why.str();
}

void Quarantine::isolate(std::size_t i, geometry::BodyState& state) {
  flags_.resize(state.size(), 0);
  flags_[i] = 1;
  const geometry::Pose start = i < startPoses_.size() && startPoses_[i].allFinite()
                                   ? startPoses_[i]
                                   : geometry::Pose::identity();
  // Static: zero inverse mass and inertia, zero velocities (BodyState::assign).
  state.assign(i, geometry::MotionType::Static, start, Eigen::Vector3d::Zero(),
               Eigen::Vector3d::Zero(), 0.0, Eigen::Matrix3d::Zero());
}

std::vector<QuarantineEvent> Quarantine::guardTrees(ArticulationStage& trees,
                                                    geometry::BodyState& state,
                                                    const QuarantineSettings& limits) const {
  std::vector<QuarantineEvent> events;
  for (std::size_t k = 0; k < trees.slots() && k < startQ_.size(); ++k) {
    const geometry::ArticulationId id = trees.idAt(k);
    if (!id.valid()) continue;  // removed
    const Eigen::VectorXd& q = trees.q(id);
    const Eigen::VectorXd& qd = trees.qd(id);
    std::string reason;
    if (!q.allFinite())
      reason = "non-finite joint positions";
    else if (!qd.allFinite())
      reason = "non-finite joint velocities";
    else if (qd.size() > 0 && qd.cwiseAbs().maxCoeff() > limits.maxAngularSpeed)
      reason = "a joint rate beyond the limit";
    if (reason.empty()) continue;
    trees.setState(id, startQ_[k], Eigen::VectorXd::Zero(qd.size()), state);
    events.push_back({{}, id, {}, reason});  // the World fills in the name
  }
  return events;
}

}  // namespace coulomb::engine
