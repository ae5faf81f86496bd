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

void validateInertia(const TreeLink& link, int index) {
  const geometry::SpatialInertia& inertia = link.inertia;
  const bool finite = std::isfinite(inertia.mass) && inertia.centerOfMass.allFinite() &&
                      inertia.inertiaAboutCom.allFinite();
  if (!finite)
    throw std::invalid_argument(describe(link, index) + ": inertia has a non-finite value");
  if (inertia.mass == 0.0) {  // a frame (URDF link without <inertial>): inertia >= 0 only
    const Eigen::Matrix3d& i = inertia.inertiaAboutCom;
    if (!i.isApprox(i.transpose(), 1e-12) ||
        geometry::principalAxes(i).moments.minCoeff() < -1e-12 * (1.0 + i.norm()))
      throw std::invalid_argument(describe(link, index) +
                                  ": a massless link's inertia must be symmetric and >= 0");
    return;
  }
  if (inertia.inertiaAboutCom.isZero(0.0) && inertia.mass > 0.0) return;  // a point mass
  if (const auto problem = geometry::checkPhysicalValidity(inertia))
    throw std::invalid_argument(describe(link, index) + ": invalid inertia: " + *problem);
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
