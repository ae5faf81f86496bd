#include <coulomb/engine/CoulombError.hpp>
#include <coulomb/engine/JointStage.hpp>
#include <coulomb/integrators/PredictedStateCorrection.hpp>
#include <coulomb/joints/EmitRows.hpp>
#include <coulomb/joints/GeometricStiffness.hpp>
#include <coulomb/joints/JointConstraint.hpp>

#include <algorithm>
#include <chrono>
#include <map>

namespace coulomb::engine {
namespace {

using Twist = Eigen::Matrix<double, 6, 1>;

geometry::Pose poseOf(const geometry::BodyState& state, const geometry::BodyId& id) {
  return id.valid() ? state.poses[id.index] : geometry::Pose::identity();
}

Twist twistOf(const geometry::BodyState& state, const geometry::BodyId& id) {
  Twist t = Twist::Zero();
  if (id.valid()) t << state.linearVelocities[id.index], state.angularVelocities[id.index];
  return t;
}

}  // namespace

geometry::JointId JointStage::create(joints::JointDef def) {
  std::size_t slot = records_.size();
  if (!freeSlots_.empty()) {
    const auto lowest = std::min_element(freeSlots_.begin(), freeSlots_.end());
    slot = *lowest;
    freeSlots_.erase(lowest);
  } else {
    records_.emplace_back();
  }
  Record& r = records_[slot];
  const std::uint32_t generation = r.generation;
  r = Record{};
  r.def = std::move(def);
  r.generation = generation;
  r.alive = true;
  return {static_cast<std::uint32_t>(slot), generation};
}

std::size_t JointStage::slotOf(geometry::JointId id) const {
  if (!contains(id))
    throw CoulombError("joint id (index " + std::to_string(id.index) + ", generation " +
                       std::to_string(id.generation) + ") is stale or invalid");
  return id.index;
}

void JointStage::remove(geometry::JointId id) {
  Record& r = records_[slotOf(id)];
  r.alive = false;
  ++r.generation;
  freeSlots_.push_back(id.index);
}

bool JointStage::contains(geometry::JointId id) const {
  return id.valid() && id.index < records_.size() && records_[id.index].alive &&
         records_[id.index].generation == id.generation;
}

const joints::JointDef& JointStage::def(geometry::JointId id) const {
  return records_[slotOf(id)].def;
}
const JointReaction& JointStage::reaction(geometry::JointId id) const {
  return records_[slotOf(id)].reaction;
}
bool JointStage::broken(geometry::JointId id) const {
  return records_[slotOf(id)].broken;
}

void JointStage::breakJoint(geometry::JointId id) {
  records_[slotOf(id)].broken = true;
}

std::size_t JointStage::count() const {
  return static_cast<std::size_t>(
      std::count_if(records_.begin(), records_.end(), [](const Record& r) { return r.alive; }));
}

std::vector<geometry::JointId> JointStage::jointsOf(geometry::BodyId body) const {
  std::vector<geometry::JointId> out;
  for (std::size_t i = 0; i < records_.size(); ++i)
    if (records_[i].alive && (records_[i].def.bodyA == body || records_[i].def.bodyB == body))
      out.push_back({static_cast<std::uint32_t>(i), records_[i].generation});
  return out;
}

const joints::Stabilization& JointStage::policyOf(const Record& r,
                                                  const joints::Stabilization& world) const {
  return r.def.stabilization ? *r.def.stabilization : world;
}

void JointStage::appendEdges(std::uint8_t owner, const RowContext&, StepEdges& edges) {
  const auto index = [](const geometry::BodyId& id) {
    return id.valid() ? static_cast<std::int32_t>(id.index) : ConstraintEdge::kNoBody;
  };
  for (std::size_t i = 0; i < records_.size(); ++i) {
    Record& r = records_[i];
    r.impulseOnB.setZero();
    if (!r.alive || r.broken) continue;
    edges.add(owner, static_cast<std::int32_t>(i), {index(r.def.bodyA), index(r.def.bodyB)});
  }
}

void JointStage::emitRows(std::span<const std::int32_t> items, const RowContext& context,
                          joints::RowSet& rows) {
  const geometry::BodyState& state = context.state;
  for (const std::int32_t item : items) {
    const auto slot = static_cast<std::uint32_t>(item);
    Record& r = records_[slot];
    joints::JointBodies bodies;
    bodies.poseA = poseOf(state, r.def.bodyA);
    bodies.poseB = poseOf(state, r.def.bodyB);
    bodies.twistA = twistOf(state, r.def.bodyA);
    bodies.twistB = twistOf(state, r.def.bodyB);
    const std::size_t first = rows.blocks.size();
    const int count = joints::emitJointRows(r.def, bodies, policyOf(r, context.jointPolicy),
                                            context.h, rows.blocks);
    for (int k = 0; k < count; ++k) {
      joints::RowBlock& block = rows.blocks[first + k];
      block.sourceKey = (static_cast<std::uint64_t>(slot) << 8) | static_cast<std::uint64_t>(k);
      const bool warm =
          k < static_cast<int>(r.warmStarts.size()) && r.warmStarts[k].size() == block.rows();
      block.warmStart = warm ? r.warmStarts[k] : joints::RowVector::Zero(block.rows());
    }
    r.armB = bodies.poseB.rotation * r.def.frameB.anchor;
    r.warmStarts.assign(count, joints::RowVector());
  }
}

void JointStage::storeImpulses(const joints::RowSet& rows, joints::BlockRange range,
                               const std::vector<RowBlockSlot>& slots,
                               const Eigen::VectorXd& lambda, const RowContext&) {
  for (std::size_t k = range.first; k < range.end(); ++k) {
    const joints::RowBlock& block = rows.blocks[k];
    Record& r = records_[block.sourceKey >> 8];
    const joints::RowVector impulse = lambda.segment(slots[k].offset, slots[k].rows);
    r.warmStarts[block.sourceKey & 0xff] = impulse;
    r.impulseOnB += block.jacobianB.transpose() * impulse;
  }
}

bool JointStage::stabilizedInverseInertias(const geometry::BodyState& state, double h,
                                           std::vector<Eigen::Matrix3d>& out) const {
  // Per loaded body the sum of its joints' geometric stiffness, summed in joint order (sorted by
  // (body, joint order) and merged: deterministic, and no map built on every step).
  std::vector<StiffnessTerm>& terms = stiffnessTerms_;
  terms.clear();
  const auto add = [&](const geometry::BodyId& id, const Eigen::Vector3d& force,
                       const Eigen::Vector3d& anchor) {
    if (!id.valid() || !state.isDynamic(id.index)) return;
    const Eigen::Vector3d arm = state.poses[id.index].rotation * anchor;
    terms.push_back({id.index, static_cast<std::uint32_t>(terms.size()),
                     joints::rotationalGeometricStiffness(force, arm)});
  };
  for (const Record& r : records_) {
    if (!r.alive || r.broken || r.reaction.force.isZero(0.0)) continue;
    add(r.def.bodyA, -r.reaction.force, r.def.frameA.anchor);  // the joint's force on A
    add(r.def.bodyB, r.reaction.force, r.def.frameB.anchor);
  }
  std::sort(terms.begin(), terms.end(), [](const StiffnessTerm& l, const StiffnessTerm& r) {
    return l.body != r.body ? l.body < r.body : l.order < r.order;
  });
  bool changed = false;
  for (std::size_t t = 0; t < terms.size();) {
    const std::uint32_t body = terms[t].body;
    Eigen::Matrix3d k = Eigen::Matrix3d::Zero();
    for (; t < terms.size() && terms[t].body == body; ++t) k += terms[t].stiffness;
    const Eigen::Quaterniond toPrincipal = state.poses[body].rotation * state.principalFrames[body];
    const Eigen::Matrix3d r = toPrincipal.toRotationMatrix();
    const Eigen::Matrix3d inertia = r * state.principalMoments[body].asDiagonal() * r.transpose();
    const Eigen::Matrix3d stable = joints::stabilizingInertia(inertia, k, h);
    if (stable == inertia) continue;
    if (!changed) out = state.worldInverseInertias;
    changed = true;
    out[body] = stable.inverse();
  }
  return changed;
}

void JointStage::correctDrift(geometry::BodyState& state, std::span<const std::int32_t> active,
                              const joints::Stabilization& worldPolicy, double h,
                              JointStepReport& report) {
  std::vector<const joints::JointDef*>& defs = correctionDefs_;  // kept for their storage
  std::vector<std::uint32_t>& slots = correctionSlots_;
  defs.clear();
  slots.clear();
  joints::PredictedStateSettings settings;  // the tightest of the joints' settings
  bool first = true;
  for (const std::int32_t item : active) {
    const auto slot = static_cast<std::uint32_t>(item);
    const Record& r = records_[slot];
    const joints::Stabilization& policy = policyOf(r, worldPolicy);
    if (policy.method != joints::StabilizationMethod::PredictedState) continue;
    const auto dynamic = [&](const geometry::BodyId& id) {
      return id.valid() && state.isDynamic(id.index);
    };
    if (!dynamic(r.def.bodyA) && !dynamic(r.def.bodyB)) continue;
    defs.push_back(&r.def);
    slots.push_back(slot);
    settings.iterations = first ? policy.predictedState.iterations
                                : std::max(settings.iterations, policy.predictedState.iterations);
    settings.tolerance = first ? policy.predictedState.tolerance
                               : std::min(settings.tolerance, policy.predictedState.tolerance);
    first = false;
  }
  if (defs.empty()) return;
  const auto started = std::chrono::steady_clock::now();
  integrators::PredictedStateResult& result = correctionResult_;
  integrators::correctPredictedState(state, defs, settings, h, correction_, result);
  for (std::size_t j = 0; j < slots.size(); ++j)
    records_[slots[j]].impulseOnB += result.impulsesOnB[j];
  report.correctionIterations = result.iterations;
  report.correctionError = result.finalError;
  report.correctionConverged = result.converged;
  report.correctionSeconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
}

void JointStage::projectVelocities(geometry::BodyState& state,
                                   std::span<const std::int32_t> items) {
  std::vector<const joints::JointDef*>& defs = projectionDefs_;
  defs.clear();
  for (const std::int32_t item : items)
    defs.push_back(&records_[static_cast<std::size_t>(item)].def);
  integrators::PredictedStateResult& result = projectionResult_;
  integrators::projectJointVelocities(state, defs, projection_, result);
  for (std::size_t j = 0; j < items.size(); ++j)
    records_[static_cast<std::size_t>(items[j])].impulseOnB += result.impulsesOnB[j];
}

joints::EnergyTarget JointStage::energyTarget(std::span<const std::int32_t> items,
                                              const joints::Stabilization& worldPolicy,
                                              const geometry::BodyState& state, bool& anchored,
                                              double& tolerance) const {
  using joints::EnergyTarget;
  anchored = false;
  tolerance = 0.0;
  EnergyTarget target = EnergyTarget::None;
  for (std::size_t k = 0; k < items.size(); ++k) {
    const Record& r = records_[static_cast<std::size_t>(items[k])];
    const joints::Stabilization& policy = policyOf(r, worldPolicy);
    if (policy.method != joints::StabilizationMethod::PredictedState || r.def.limit.enabled ||
        r.def.motor.enabled || r.def.friction != 0.0)
      return EnergyTarget::None;
    if (k > 0 && policy.predictedState.energy != target) return EnergyTarget::None;
    target = policy.predictedState.energy;
    tolerance = std::max(tolerance, policy.predictedState.tolerance);
    for (const geometry::BodyId& id : {r.def.bodyA, r.def.bodyB}) {
      if (!id.valid() || state.motionTypes[id.index] == geometry::MotionType::Static)
        anchored = true;
      else if (!state.isDynamic(id.index))
        return EnergyTarget::None;  // a kinematic body drives the island: it does work
    }
  }
  return target;
}

bool JointStage::projectsEnergy(const joints::Stabilization& worldPolicy) const {
  return std::any_of(records_.begin(), records_.end(), [&](const Record& r) {
    const joints::Stabilization& policy = policyOf(r, worldPolicy);
    return r.alive && !r.broken && policy.method == joints::StabilizationMethod::PredictedState &&
           policy.predictedState.energy != joints::EnergyTarget::None;
  });
}

bool JointStage::boundaryVelocities(std::span<const std::int32_t> items,
                                    const geometry::BodyState& state,
                                    std::span<const geometry::Pose> poses,
                                    std::span<const Eigen::Vector3d> linear,
                                    std::span<const Eigen::Vector3d> angular,
                                    std::vector<Eigen::Vector3d>& out) const {
  out.resize(poses.size());
  if (reached_.size() < poses.size()) reached_.resize(poses.size(), 0);
  // Only the island's entries are marked, and cleared again on the way out: a world of many
  // small islands pays for each island's joints, not for all its bodies.
  struct ClearMarks {
    const JointStage& stage;
    std::span<const std::int32_t> items;
    ~ClearMarks() {
      for (const std::int32_t item : items)
        for (const geometry::BodyId& id :
             {stage.records_[static_cast<std::size_t>(item)].def.bodyA,
              stage.records_[static_cast<std::size_t>(item)].def.bodyB})
          if (id.valid()) stage.reached_[id.index] = 0;
    }
  } clearMarks{*this, items};
  const auto worldAnchor = [&](const geometry::BodyId& id, const joints::JointFrame& frame) {
    return id.valid() ? Eigen::Vector3d(poses[id.index].apply(frame.anchor)) : frame.anchor;
  };
  const auto ground = [&](const geometry::BodyId& id) {  // the world or a static body
    return !id.valid() || state.motionTypes[id.index] == geometry::MotionType::Static;
  };
  std::int32_t lowest = -1;
  for (const std::int32_t item : items) {
    const joints::JointDef& def = records_[static_cast<std::size_t>(item)].def;
    if (def.type == joints::JointType::Prismatic) return false;
    for (const geometry::BodyId& id : {def.bodyA, def.bodyB})
      if (id.valid() && !ground(id) && (lowest < 0 || static_cast<std::int32_t>(id.index) < lowest))
        lowest = static_cast<std::int32_t>(id.index);
  }
  // Bodies held to the ground first.
  bool anchored = false;
  for (const std::int32_t item : items) {
    const joints::JointDef& def = records_[static_cast<std::size_t>(item)].def;
    const bool groundA = ground(def.bodyA), groundB = ground(def.bodyB);
    if (groundA == groundB) continue;
    const geometry::BodyId body = groundA ? def.bodyB : def.bodyA;
    const joints::JointFrame& frame = groundA ? def.frameB : def.frameA;
    const std::uint32_t i = body.index;
    if (reached_[i] != 0) continue;
    out[i] = angular[i].cross(poses[i].position - worldAnchor(body, frame));
    reached_[i] = 1;
    anchored = true;
  }
  if (!anchored) {
    if (lowest < 0) return true;
    out[lowest] = linear[lowest];
    reached_[lowest] = 1;
  }
  // Across the joints until nothing new is reached (one pass for a chain listed from its anchor).
  for (bool progress = true; progress;) {
    progress = false;
    for (const std::int32_t item : items) {
      const joints::JointDef& def = records_[static_cast<std::size_t>(item)].def;
      if (ground(def.bodyA) || ground(def.bodyB)) continue;  // reached from the anchors above
      const std::uint32_t a = def.bodyA.index, b = def.bodyB.index;
      if ((reached_[a] != 0) == (reached_[b] != 0)) continue;
      const bool fromA = reached_[a] != 0;
      const std::uint32_t known = fromA ? a : b, next = fromA ? b : a;
      const Eigen::Vector3d p =
          fromA ? worldAnchor(def.bodyB, def.frameB) : worldAnchor(def.bodyA, def.frameA);
      out[next] = out[known] + angular[known].cross(p - poses[known].position) +
                  angular[next].cross(poses[next].position - p);
      reached_[next] = 1;
      progress = true;
    }
  }
  return true;
}

void JointStage::finishStep(const geometry::BodyState& state, std::span<const std::int32_t> active,
                            double h, JointStepReport& report) {
  for (const std::int32_t item : active) {
    const auto slot = static_cast<std::uint32_t>(item);
    Record& r = records_[slot];
    ++report.joints;
    r.reaction.force = r.impulseOnB.head<3>() / h;
    r.reaction.torque = r.impulseOnB.tail<3>() / h - r.armB.cross(r.reaction.force);
    if (r.reaction.force.norm() > r.def.breakForce ||
        r.reaction.torque.norm() > r.def.breakTorque) {
      r.broken = true;
      report.broken.push_back({slot, r.generation});
    }
    const joints::ConstraintEval eval =
        joints::evaluateJoint(r.def, poseOf(state, r.def.bodyA), poseOf(state, r.def.bodyB));
    const joints::JointError error = joints::jointError(r.def, eval);
    report.maxLinearError = std::max(report.maxLinearError, error.linear);
    report.maxAngularError = std::max(report.maxAngularError, error.angular);
  }
}

}  // namespace coulomb::engine
