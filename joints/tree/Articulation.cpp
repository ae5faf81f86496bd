#include <coulomb/joints/tree/Articulation.hpp>

#include <cmath>
#include <sstream>
#include <stdexcept>
#include <utility>

namespace coulomb::joints::tree {

namespace {
std::string describe(const TreeLink& link, int index) {
  std::ostringstream out;
  out << "link " << index << " '" << link.name << "'";
  return out.str();
}

/// What the tree's algorithms need of a link's inertia: finite, mass >= 0, a symmetric positive
/// semidefinite tensor. Nothing more: the triangle inequality of the principal moments (which
/// every real mass distribution satisfies, geometry::checkPhysicalValidity) is not needed by ABA,
/// RNEA or CRBA, and URDF files from CAD often break it (docs/urdf.md, "Inertia policy"). A
/// joint whose subtree offers no inertia along its motion is caught where it matters, by ABA's
/// D^-1 (TreeDynamics.hpp).
void validateInertia(const TreeLink& link, int index) {
  const geometry::SpatialInertia& inertia = link.inertia;
  const bool finite = std::isfinite(inertia.mass) && inertia.centerOfMass.allFinite() &&
                      inertia.inertiaAboutCom.allFinite();
  if (!finite)
    throw std::invalid_argument(describe(link, index) + ": inertia has a non-finite value");
  if (inertia.mass < 0.0) {
    std::ostringstream out;
    out << describe(link, index) << ": invalid inertia: mass must be >= 0 (got " << inertia.mass
        << ")";
    throw std::invalid_argument(out.str());
  }
  const Eigen::Matrix3d& i = inertia.inertiaAboutCom;
  const Eigen::Vector3d moments = geometry::principalAxes(i).moments;  // ascending
  if (!i.isApprox(i.transpose(), 1e-9) || moments[0] < -1e-12 * (1.0 + i.norm())) {
    std::ostringstream out;
    out << describe(link, index)
        << ": invalid inertia: the tensor must be symmetric and positive semidefinite (principal "
           "moments "
        << moments.transpose() << " kg m^2)";
    throw std::invalid_argument(out.str());
  }
}
}  // namespace

Articulation::Articulation(std::vector<TreeLink> links, const Eigen::Vector3d& gravity)
    : links_(std::move(links)), gravity_(gravity) {
  if (!gravity_.allFinite()) throw std::invalid_argument("articulation: gravity is not finite");
  for (int i = 0; i < linkCount(); ++i) {
    const TreeLink& l = link(i);
    if (l.parent < -1 || l.parent >= i) {
      std::ostringstream out;
      out << describe(l, i) << ": parent index " << l.parent
          << " must be -1 (world) or come before the link (topological order)";
      throw std::invalid_argument(out.str());
    }
    try {
      l.joint.validate();
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument(describe(l, i) + ": " + e.what());
    }
    validateInertia(l, i);
    qIndex_.push_back(nq_);
    vIndex_.push_back(nv_);
    nq_ += l.joint.nq();
    nv_ += l.joint.nv();
    spatialInertia_.push_back(l.inertia.matrix());
    subspace_.push_back(l.joint.motionSubspace());
  }
}

int Articulation::findLink(const std::string& name) const {
  for (int i = 0; i < linkCount(); ++i)
    if (link(i).name == name) return i;
  return -1;
}

bool Articulation::hasFloatingBase() const {
  for (const TreeLink& l : links_)
    if (l.parent == -1 && l.joint.type == TreeJointType::Floating) return true;
  return false;
}

Eigen::VectorXd Articulation::neutralConfiguration() const {
  Eigen::VectorXd q(nq_);
  for (int i = 0; i < linkCount(); ++i)
    q.segment(qIndex(i), link(i).joint.nq()) = link(i).joint.neutralConfiguration();
  return q;
}

void Articulation::checkConfiguration(const Eigen::VectorXd& q) const {
  if (q.size() != nq_) {
    std::ostringstream out;
    out << "articulation: q has " << q.size() << " values, expected nq = " << nq_;
    throw std::invalid_argument(out.str());
  }
  for (int i = 0; i < linkCount(); ++i) {
    const TreeJoint& joint = link(i).joint;
    const auto segment = q.segment(qIndex(i), joint.nq());
    if (!segment.allFinite())
      throw std::invalid_argument(describe(link(i), i) + ": joint '" + joint.name +
                                  "' has a non-finite coordinate in q");
    const int quaternionStart = joint.type == TreeJointType::Floating ? 3 : 0;
    if ((joint.type == TreeJointType::Spherical || joint.type == TreeJointType::Floating) &&
        segment.segment(quaternionStart, 4).norm() < 1e-6)
      throw std::invalid_argument(describe(link(i), i) + ": joint '" + joint.name +
                                  "' has a zero quaternion in q");
  }
}

void Articulation::checkVelocity(const Eigen::VectorXd& qd, const char* what) const {
  if (qd.size() != nv_) {
    std::ostringstream out;
    out << "articulation: " << what << " has " << qd.size() << " values, expected nv = " << nv_;
    throw std::invalid_argument(out.str());
  }
  if (qd.allFinite()) return;
  for (int i = 0; i < linkCount(); ++i)
    if (!qd.segment(vIndex(i), link(i).joint.nv()).allFinite())
      throw std::invalid_argument(describe(link(i), i) + ": joint '" + link(i).joint.name +
                                  "' has a non-finite value in " + what);
}

}  // namespace coulomb::joints::tree
