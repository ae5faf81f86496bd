// Articulations in the World: creation, state, proxies, the velocity prediction and the position
// update. Rows, W blocks and impulses are in ArticulationRows.cpp.
#include <coulomb/engine/ArticulationStage.hpp>
#include <coulomb/engine/BodyBuilder.hpp>
#include <coulomb/engine/CoulombError.hpp>
#include <coulomb/geometry/MassProperties.hpp>
#include <coulomb/integrators/ArticulationIntegrator.hpp>
#include <coulomb/joints/tree/TreeKinematics.hpp>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <variant>

namespace coulomb::engine {

using geometry::ArticulationId;
using geometry::BodyId;
using joints::tree::Articulation;
using joints::tree::TreeLink;

namespace {

std::string quoted(const std::string& name) {
  return "articulation '" + name + "'";
}

/// Link inertia: the explicit one, or the shapes' at the density (planes excluded).
geometry::SpatialInertia linkInertia(const ArticulationLinkDesc& link,
                                     const WorldSettings& settings, const std::string& where) {
  if (link.inertia) return *link.inertia;
  const double density = link.density.value_or(settings.defaultDensity);
  if (!std::isfinite(density) || density <= 0.0)
    throw CoulombError(where + ": density must be finite and > 0 kg/m^3");
  geometry::SpatialInertia sum;
  for (const ShapeDesc& s : link.shapes) {
    if (std::holds_alternative<geometry::Plane>(s.shape)) continue;
    if (auto problem = geometry::validateShape(s.shape))
      throw CoulombError(where + ": " + *problem);
    if (auto* hull = std::get_if<geometry::ConvexHull>(&s.shape); hull && hull->triangles.empty())
      throw CoulombError(where + ": " + kHullNeedsFaces);
    sum = sum + geometry::computeMassProperties(s.shape, density).transformed(s.localPose);
  }
  return sum;  // mass 0 without shapes: a massless frame (allowed by the tree model)
}

bool isOneDof(const joints::tree::TreeJoint& joint) {
  using joints::tree::TreeJointType;
  return joint.type == TreeJointType::Revolute || joint.type == TreeJointType::Continuous ||
         joint.type == TreeJointType::Prismatic;
}

void checkMotorsAndCouplings(const ArticulationDesc& desc, const Articulation& model,
                             const std::string& who) {
  const int n = model.linkCount();
  auto oneDofLink = [&](int link, const std::string& what) {
    if (link < 0 || link >= n)
      throw CoulombError(who + ": " + what + " names link " + std::to_string(link) +
                         " (must be < " + std::to_string(n) + ")");
    if (!isOneDof(model.link(link).joint))
      throw CoulombError(who + ": " + what + " on link '" + model.link(link).name + "': joint '" +
                         model.link(link).joint.name +
                         "' is not revolute, continuous or prismatic");
  };
  for (std::size_t k = 0; k < desc.motors.size(); ++k) {
    const JointMotorDesc& m = desc.motors[k];
    const std::string what = "motor " + std::to_string(k);
    oneDofLink(m.link, what);
    if (!std::isfinite(m.target)) throw CoulombError(who + ": " + what + ": target is not finite");
    if (!std::isfinite(m.maxEffort) || m.maxEffort <= 0.0)
      throw CoulombError(who + ": " + what + ": max effort must be finite and > 0");
    if (!(m.positionGain > 0.0 && m.positionGain <= 1.0))
      throw CoulombError(who + ": " + what + ": position gain must be in (0, 1]");
    if (!(m.maxVelocity > 0.0))
      throw CoulombError(who + ": " + what + ": max velocity must be > 0");
  }
  for (std::size_t k = 0; k < desc.couplings.size(); ++k) {
    const JointCouplingDesc& c = desc.couplings[k];
    const std::string what = "coupling " + std::to_string(k);
    oneDofLink(c.follower, what);
    oneDofLink(c.leader, what);
    if (c.follower == c.leader)
      throw CoulombError(who + ": " + what + ": follower and leader are the same joint");
    if (!std::isfinite(c.multiplier) || !std::isfinite(c.offset))
      throw CoulombError(who + ": " + what + ": multiplier and offset must be finite");
  }
  for (std::size_t k = 0; k < desc.jointTorques.size(); ++k) {
    const JointTorqueDesc& t = desc.jointTorques[k];
    const std::string what = "joint torque " + std::to_string(k);
    oneDofLink(t.link, what);
    if (!std::isfinite(t.torque)) throw CoulombError(who + ": " + what + ": torque is not finite");
  }
  for (int i = 0; i < n; ++i) {
    const double f = desc.links[static_cast<std::size_t>(i)].jointFriction;
    if (!std::isfinite(f) || f < 0.0)
      throw CoulombError(who + ": link '" + model.link(i).name +
                         "': joint friction must be finite and >= 0");
    if (f > 0.0) oneDofLink(i, "joint friction");
  }
}

}  // namespace

ArticulationStage::Prepared ArticulationStage::prepare(const ArticulationDesc& desc,
                                                       const WorldSettings& settings) const {
  const std::string who = quoted(desc.name);
  if (desc.links.empty()) throw CoulombError(who + ": needs at least one link");
  if (!std::isfinite(desc.errorReduction) || desc.errorReduction < 0.0 || desc.errorReduction > 1.0)
    throw CoulombError(who + ": error_reduction must be in [0, 1]");
  Prepared out;
  for (std::size_t i = 0; i < desc.links.size(); ++i) {
    const ArticulationLinkDesc& l = desc.links[i];
    const std::string where = who + " link '" + l.name + "'";
    out.links.push_back(TreeLink{l.name, l.parent, l.joint, linkInertia(l, settings, where)});
  }
  try {
    out.model = std::make_unique<Articulation>(out.links, settings.gravity);
    out.q = desc.q.value_or(out.model->neutralConfiguration());
    out.qd = desc.qd.value_or(Eigen::VectorXd::Zero(out.model->nv()));
    out.model->checkConfiguration(out.q);
    out.model->checkVelocity(out.qd);
  } catch (const std::invalid_argument& e) {
    throw CoulombError(who + ": " + e.what());
  }
  const int n = out.model->linkCount();
  for (const LoopClosureDesc& c : desc.loopClosures) {
    if (c.linkA < 0 || c.linkA >= n || c.linkB < -1 || c.linkB >= n || c.linkA == c.linkB)
      throw CoulombError(who + ": a loop closure names links " + std::to_string(c.linkA) + " and " +
                         std::to_string(c.linkB) + " (must be distinct, < " + std::to_string(n) +
                         ", linkB -1 = world)");
    if (!c.anchorA.allFinite() || !c.anchorB.allFinite())
      throw CoulombError(who + ": a loop closure anchor is not finite");
    if (!c.axes[0] && !c.axes[1] && !c.axes[2])
      throw CoulombError(who + ": a loop closure constrains no axis");
  }

  checkMotorsAndCouplings(desc, *out.model, who);

  const joints::tree::TreeKinematics kin = joints::tree::forwardKinematics(*out.model, out.q);
  for (int i = 0; i < n; ++i) {
    BodyDesc proxy;
    proxy.name = desc.name + "/" + desc.links[i].name;
    proxy.motionType = geometry::MotionType::Kinematic;
    proxy.pose = kin.worldPoses[i];
    proxy.shapes = desc.links[i].shapes;
    (void)resolveBody(proxy, settings);  // validates the shapes; throws naming the proxy
    out.proxies.push_back(std::move(proxy));
  }
  out.desc = desc;
  return out;
}

ArticulationId ArticulationStage::add(Prepared prepared, std::vector<BodyId> proxies,
                                      geometry::BodyState& state) {
  Record r;
  r.name = prepared.desc.name;
  r.links = std::move(prepared.links);
  r.model = std::move(prepared.model);
  r.q = std::move(prepared.q);
  r.qd = std::move(prepared.qd);
  r.tau = Eigen::VectorXd::Zero(r.model->nv());
  r.linkBodies = std::move(proxies);
  r.closures = prepared.desc.loopClosures;
  r.closureWarm.assign(r.closures.size(), Eigen::Vector3d::Zero());
  r.lowerWarm.assign(r.links.size(), 0.0);
  r.upperWarm.assign(r.links.size(), 0.0);
  r.motors = prepared.desc.motors;
  r.motorWarm.assign(r.motors.size(), 0.0);
  r.couplings = prepared.desc.couplings;
  r.couplingWarm.assign(r.couplings.size(), 0.0);
  for (const ArticulationLinkDesc& link : prepared.desc.links)
    r.friction.push_back(link.jointFriction);
  for (const JointMotorDesc& motor : r.motors) r.friction[motor.link] = 0.0;  // the motor bounds it
  r.frictionWarm.assign(r.links.size(), 0.0);
  r.constantTau = Eigen::VectorXd::Zero(r.model->nv());
  for (const JointTorqueDesc& t : prepared.desc.jointTorques)
    r.constantTau[r.model->vIndex(t.link)] += t.torque;
  r.errorReduction = prepared.desc.errorReduction;
  r.selfCollision = prepared.desc.selfCollision;
  r.userData = prepared.desc.userData;
  const auto slot = static_cast<std::int32_t>(records_.size());
  for (int i = 0; i < static_cast<int>(r.linkBodies.size()); ++i) {
    const std::uint32_t body = r.linkBodies[i].index;
    if (linkOfBody_.size() <= body) linkOfBody_.resize(body + 1);
    linkOfBody_[body] = {slot, i};
  }
  updateProxies(r, state);
  records_.push_back(std::move(r));
  return {static_cast<std::uint32_t>(slot), records_.back().generation};
}

std::vector<BodyId> ArticulationStage::remove(ArticulationId id) {
  Record& r = record(id);
  for (const BodyId& body : r.linkBodies) linkOfBody_[body.index] = {};
  std::vector<BodyId> proxies = std::move(r.linkBodies);
  const std::uint32_t generation = r.generation + 1;
  r = Record{};  // frees the model and the state
  r.alive = false;
  r.generation = generation;
  return proxies;
}

bool ArticulationStage::contains(ArticulationId id) const {
  return id.valid() && id.index < records_.size() && records_[id.index].alive &&
         records_[id.index].generation == id.generation;
}
std::size_t ArticulationStage::count() const {
  return static_cast<std::size_t>(
      std::count_if(records_.begin(), records_.end(), [](const Record& r) { return r.alive; }));
}
ArticulationId ArticulationStage::idAt(std::size_t slot) const {
  if (slot >= records_.size() || !records_[slot].alive) return {};
  return {static_cast<std::uint32_t>(slot), records_[slot].generation};
}
std::uint64_t ArticulationStage::userData(ArticulationId id) const {
  return record(id).userData;
}

ArticulationStage::Record& ArticulationStage::record(ArticulationId id) {
  if (!contains(id))
    throw CoulombError("articulation id (index " + std::to_string(id.index) + ") is invalid");
  return records_[id.index];
}
const ArticulationStage::Record& ArticulationStage::record(ArticulationId id) const {
  if (!contains(id))
    throw CoulombError("articulation id (index " + std::to_string(id.index) + ") is invalid");
  return records_[id.index];
}

const Articulation& ArticulationStage::model(ArticulationId id) const {
  return *record(id).model;
}
const Eigen::VectorXd& ArticulationStage::q(ArticulationId id) const {
  return record(id).q;
}
const Eigen::VectorXd& ArticulationStage::qd(ArticulationId id) const {
  return record(id).qd;
}

BodyId ArticulationStage::linkBody(ArticulationId id, int link) const {
  const Record& r = record(id);
  if (link < 0 || link >= static_cast<int>(r.linkBodies.size()))
    throw CoulombError(quoted(r.name) + ": no link " + std::to_string(link));
  return r.linkBodies[link];
}
const geometry::Pose& ArticulationStage::linkPose(ArticulationId id, int link) const {
  const Record& r = record(id);
  if (link < 0 || link >= static_cast<int>(r.linkPoses.size()))
    throw CoulombError(quoted(r.name) + ": no link " + std::to_string(link));
  return r.linkPoses[link];
}

void ArticulationStage::setState(ArticulationId id, const Eigen::VectorXd& q,
                                 const Eigen::VectorXd& qd, geometry::BodyState& state) {
  Record& r = record(id);
  try {
    r.model->checkConfiguration(q);
    r.model->checkVelocity(qd);
  } catch (const std::invalid_argument& e) {
    throw CoulombError(quoted(r.name) + ": " + e.what());
  }
  r.q = q;
  r.qd = qd;
  r.qdStart = qd;  // set within a step (the guard's reset), the Runge-Kutta step starts here
  updateProxies(r, state);
}

void ArticulationStage::applyJointForces(ArticulationId id, const Eigen::VectorXd& tau) {
  Record& r = record(id);
  if (tau.size() != r.model->nv() || !tau.allFinite())
    throw CoulombError(quoted(r.name) + ": joint forces need " + std::to_string(r.model->nv()) +
                       " finite values (got " + std::to_string(tau.size()) + ")");
  const Eigen::VectorXd sum = r.tau + tau;  // finite calls can still add up to +-inf
  if (!sum.allFinite())
    throw CoulombError(quoted(r.name) + ": the joint forces accumulated for this step overflow");
  r.tau = sum;
}

void ArticulationStage::setMotorTarget(ArticulationId id, int motor, double target) {
  Record& r = record(id);
  if (motor < 0 || motor >= static_cast<int>(r.motors.size()))
    throw CoulombError(quoted(r.name) + ": no motor " + std::to_string(motor) + " (it has " +
                       std::to_string(r.motors.size()) + ")");
  if (!std::isfinite(target))
    throw CoulombError(quoted(r.name) + ": motor " + std::to_string(motor) +
                       ": target is not finite");
  r.motors[motor].target = target;
}

int ArticulationStage::motorOf(ArticulationId id, const std::string& joint) const {
  const Record& r = record(id);
  std::string names;
  for (std::size_t k = 0; k < r.motors.size(); ++k) {
    const std::string& name = r.model->link(r.motors[k].link).joint.name;
    if (name == joint) return static_cast<int>(k);
    names += (names.empty() ? "" : ", ") + quoted(name);
  }
  throw CoulombError(quoted(r.name) + ": no motor on a joint named " + quoted(joint) +
                     " (motorised joints: " + (names.empty() ? "none" : names) + ")");
}

const std::vector<JointMotorDesc>& ArticulationStage::motors(ArticulationId id) const {
  return record(id).motors;
}

void ArticulationStage::updateProxies(Record& r, geometry::BodyState& state) const {
  joints::tree::forwardKinematics(*r.model, r.q, r.proxyKinematics);
  joints::tree::linkVelocities(*r.model, r.proxyKinematics, r.qd, r.proxyVelocities);
  const joints::tree::TreeKinematics& kin = r.proxyKinematics;
  const std::vector<geometry::Vector6d>& v = r.proxyVelocities;
  r.linkPoses = kin.worldPoses;
  for (std::size_t i = 0; i < r.linkBodies.size(); ++i) {
    const std::uint32_t body = r.linkBodies[i].index;
    const Eigen::Matrix3d R = kin.worldPoses[i].rotation.toRotationMatrix();
    state.poses[body] = kin.worldPoses[i];
    state.angularVelocities[body] = R * v[i].head<3>();  // (omega; v_origin) in the link frame
    state.linearVelocities[body] = R * v[i].tail<3>();
  }
}

void ArticulationStage::predictVelocities(const Eigen::Vector3d& gravity, double h,
                                          geometry::BodyState& state, StepExecutor& executor) {
  executor.forEach(records_.size(), [&](std::size_t a) {
    Record& r = records_[a];
    if (!r.alive) return;
    if (r.model->gravity() != gravity) r.model = std::make_unique<Articulation>(r.links, gravity);
    r.totalTau = r.tau;
    r.totalTau += r.constantTau;
    r.qdStart = r.qd;
    r.constrained = false;
    integrators::predictArticulationVelocity(*r.model, r.q, r.qd, r.totalTau, h, r.aba, r.qdd);
    updateProxies(r, state);
  });
}

void ArticulationStage::integratePositions(double h, TreeIntegrator integrator,
                                           geometry::BodyState& state, StepExecutor& executor) {
  executor.forEach(records_.size(), [&](std::size_t a) {
    Record& r = records_[a];
    if (!r.alive) return;
    if (integrator == TreeIntegrator::RungeKutta && !r.constrained) {
      if (!r.integration) r.integration = std::make_shared<integrators::TreeStepScratch>();
      r.qd = r.qdStart;
      integrators::rungeKuttaStep(*r.model, r.q, r.qd, r.totalTau, h, r.aba, *r.integration);
    } else {
      integrators::integrateConfiguration(*r.model, r.q, r.qd, h);
    }
    updateProxies(r, state);
  });
}

void ArticulationStage::clearForces() {
  for (Record& r : records_) r.tau.setZero();  // empty for a removed one
}

bool ArticulationStage::keepPair(std::size_t bodyA, std::size_t bodyB) const {
  const LinkRef a = linkOf(bodyA), b = linkOf(bodyB);
  if (!a.valid() || !b.valid() || a.articulation != b.articulation) return true;
  const Record& r = records_[a.articulation];
  if (!r.selfCollision) return false;
  return r.model->parent(a.link) != b.link && r.model->parent(b.link) != a.link;
}

void ArticulationStage::markIslandBodies(std::vector<std::uint8_t>& mask) const {
  for (const Record& r : records_) {
    if (!r.alive) continue;
    for (const BodyId& body : r.linkBodies) mask[body.index] = 0;
    mask[r.linkBodies.front().index] = r.model->nv() > 0 ? 1 : 0;
  }
}

void ArticulationStage::mapEdges(std::vector<ConstraintEdge>& edges) const {
  auto representative = [&](std::int32_t body) {
    if (body < 0 || !isLink(static_cast<std::size_t>(body))) return body;
    const Record& r = records_[linkOfBody_[body].articulation];
    return static_cast<std::int32_t>(r.linkBodies.front().index);
  };
  for (ConstraintEdge& e : edges) {
    e.bodyA = representative(e.bodyA);
    e.bodyB = representative(e.bodyB);
  }
}

}  // namespace coulomb::engine
