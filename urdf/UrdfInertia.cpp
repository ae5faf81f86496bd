// The inertia policy of URDF bodies (UrdfInertia.hpp, docs/urdf.md "Inertia policy").
#include <coulomb/urdf/UrdfInertia.hpp>

#include <algorithm>
#include <cmath>
#include <sstream>

namespace coulomb::engine::io {
namespace {

/// A principal moment below -kRoundOff times the largest is negative: the eigen-solver's
/// round-off is ~1e-16 of it, so singular tensors (a rod, a flat plate's limit) stay
/// semidefinite; and joints::tree::Articulation, whose tolerance is wider, accepts what is kept.
constexpr double kRoundOff = 1e-12;
/// A repair lifts the moments below this fraction of the largest to it.
constexpr double kMomentFloor = 1e-9;

bool semidefinite(const Eigen::Vector3d& ascending) {
  return ascending[0] >= -kRoundOff * std::abs(ascending[2]);
}

Eigen::Matrix3d fromPrincipal(const geometry::PrincipalAxes& axes, const Eigen::Vector3d& m) {
  const Eigen::Matrix3d r = axes.rotation.toRotationMatrix();
  return r * m.asDiagonal() * r.transpose();
}

/// Lifts the moments that ABA cannot use (below the floor) to it; the others stay.
void repairIndefinite(UrdfBody& body, std::vector<std::string>& warnings) {
  const geometry::PrincipalAxes axes = geometry::principalAxes(body.inertia.inertiaAboutCom);
  const Eigen::Vector3d before = axes.moments;
  // The largest moment in magnitude: never zero here (a zero tensor is semidefinite).
  const double floor = kMomentFloor * before.cwiseAbs().maxCoeff();
  const Eigen::Vector3d after = before.cwiseMax(floor);
  body.inertia.inertiaAboutCom = fromPrincipal(axes, after);
  std::ostringstream note;
  note << "body '" << body.name << "': inertia not positive semidefinite (principal moments "
       << before.transpose() << " kg m^2), which reduced coordinates cannot use; moments below "
       << kMomentFloor << " of the largest lifted: " << after.transpose();
  warnings.push_back(note.str());
}

UrdfInertiaStatus classify(const UrdfBody& body) {
  const geometry::SpatialInertia& inertia = body.inertia;
  if (inertia.mass == 0.0) return UrdfInertiaStatus::Massless;
  if (inertia.inertiaAboutCom.isZero(0.0)) return UrdfInertiaStatus::PointMass;
  return body.inertiaValid ? UrdfInertiaStatus::Physical : UrdfInertiaStatus::AsWritten;
}

}  // namespace

void applyTreeInertiaPolicy(std::vector<UrdfBody>& bodies, const UrdfOptions& options,
                            std::vector<std::string>& warnings) {
  const std::size_t n = bodies.size();
  std::vector<bool> hasInertia(n, false);
  for (std::size_t i = n; i-- > 0;) {
    const UrdfBody& body = bodies[i];
    hasInertia[i] =
        hasInertia[i] || body.inertia.mass > 0.0 || !body.inertia.inertiaAboutCom.isZero(0.0);
    if (body.parent >= 0 && hasInertia[i]) hasInertia[static_cast<std::size_t>(body.parent)] = true;
  }
  std::vector<std::string> massless, notPhysical;
  for (std::size_t i = 0; i < n; ++i) {
    UrdfBody& body = bodies[i];
    bool repaired = false;
    if (body.joint.nv() > 0 && !hasInertia[i]) {
      // ABA would divide by zero: nothing behind this joint resists its motion.
      body.inertia = {options.masslessSubtreeMass, Eigen::Vector3d::Zero(),
                      options.masslessSubtreeInertia * Eigen::Matrix3d::Identity()};
      massless.push_back(body.name);
      repaired = true;
    } else if (!semidefinite(geometry::principalAxes(body.inertia.inertiaAboutCom).moments)) {
      repairIndefinite(body, warnings);
      repaired = true;
    }
    body.inertiaValid = !geometry::checkPhysicalValidity(body.inertia).has_value();
    body.inertiaStatus = repaired ? UrdfInertiaStatus::Repaired : classify(body);
    if (body.inertiaStatus == UrdfInertiaStatus::AsWritten) {
      std::ostringstream note;
      note << body.name << " (moments "
           << geometry::principalAxes(body.inertia.inertiaAboutCom).moments.transpose() << ")";
      notPhysical.push_back(note.str());
    }
  }
  auto list = [](const std::vector<std::string>& names) {
    std::string out;
    for (std::size_t i = 0; i < names.size() && i < 12; ++i) out += (i ? ", " : "") + names[i];
    if (names.size() > 12) out += ", ... (" + std::to_string(names.size()) + " in all)";
    return out;
  };
  if (!massless.empty())
    warnings.push_back(
        "moving joints with nothing massive behind them; given a tiny inertia so that ABA "
        "stays finite: " +
        list(massless));
  if (!notPhysical.empty())
    warnings.push_back(
        "inertias no rigid body has (principal moments breaking the triangle inequality I1 + I2 "
        ">= I3, or singular), kept as written: reduced coordinates need only a positive "
        "semidefinite tensor, and other tools compute with the file's numbers [kg m^2]: " +
        list(notPhysical));
}

Eigen::Matrix3d withTriangleInequality(const Eigen::Matrix3d& inertia) {
  const geometry::PrincipalAxes axes = geometry::principalAxes(inertia);
  Eigen::Vector3d m = axes.moments;  // ascending: only I1 + I2 >= I3 can fail
  if (m[0] + m[1] >= m[2]) return inertia;
  const double lift = 0.5 * (m[2] - m[0] - m[1]);
  m[0] += lift;
  m[1] += lift;
  return fromPrincipal(axes, m);
}

}  // namespace coulomb::engine::io
