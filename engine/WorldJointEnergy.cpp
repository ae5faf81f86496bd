// World's energy projection stage (docs/architecture.md, "The step"; docs/tuning.md, "Chains
// keep their energy"): the bodies' energies and velocities at the step's start, and after the
// position update each island of ideal joints scaled back to the modified energy it started with
// (integrators/EnergyProjection.hpp).
#include <coulomb/engine/World.hpp>
#include <coulomb/integrators/EnergyProjection.hpp>

#include <algorithm>
#include <cmath>
#include <span>

namespace coulomb::engine {

namespace {

// Some body of the island is a tree's link or has an applied force or torque this step: work
// enters that the joints' energy does not account for.
bool drivenFromOutside(std::span<const std::int32_t> bodies, const geometry::BodyState& state,
                       const ArticulationStage& articulations) {
  return std::any_of(bodies.begin(), bodies.end(), [&](std::int32_t i) {
    return articulations.isLink(i) || !state.forces[i].isZero(0.0) || !state.torques[i].isZero(0.0);
  });
}

}  // namespace

void World::recordStartEnergies() {
  step_.startEnergies.clear();
  if (!joints_.projectsEnergy(settings_.jointStabilization)) return;
  step_.startEnergies.resize(state_.size());
  for (std::size_t i = 0; i < state_.size(); ++i)
    step_.startEnergies[i] = integrators::bodyEnergy(state_, i, settings_.gravity);
  step_.startPoses = state_.poses;  // (assigned: the vectors keep their storage)
}

// An island takes the symmetric step when its joints keep the exact energy (`energy: exact`) and
// nothing but gravity and ideal joints acts on it: no contact, no tree link, no applied force or
// torque, joints that JointStage::energyTarget accepts (predicted-state policy, no limit, motor,
// friction or kinematic driver), and no body under a heavy load's stabilizing inertia (there the
// joint rows turn by h omega >> 1 per step, beyond a symmetric step's stability, and the
// stabilized kick-drift step stays). Its bodies take v* = v + (h/2) g here instead of v + h g.
void World::splitJointIslandKicks() {
  step_.symmetricJoints.clear();
  if (step_.startEnergies.empty()) return;  // no joint asks for an energy target
  const Eigen::Vector3d halfKick = 0.5 * step_.h * settings_.gravity;
  for (IslandWork& island : step_.work) {
    const std::vector<std::int32_t>& joints = island.items[kJointRows];
    if (joints.empty() || !island.items[kContactRows].empty() || !island.items[kTreeRows].empty())
      continue;
    bool anchored = false;
    double tolerance = 0.0;
    if (joints_.energyTarget(joints, settings_.jointStabilization, state_, anchored, tolerance) !=
        joints::EnergyTarget::Exact)
      continue;
    bool stabilized = false;
    for (const std::int32_t i : island.island.bodies)
      stabilized = stabilized || (step_.stabilized &&
                                  step_.solveInverseInertias[i] != state_.worldInverseInertias[i]);
    if (stabilized || drivenFromOutside(island.island.bodies, state_, articulations_)) continue;
    island.symmetricStep = true;
    for (const std::int32_t i : island.island.bodies)
      if (state_.isDynamic(i)) state_.linearVelocities[i] -= halfKick;
    step_.symmetricJoints.insert(step_.symmetricJoints.end(), joints.begin(), joints.end());
  }
}

void World::finishJointIslandKicks() {
  if (step_.symmetricJoints.empty()) return;
  const Eigen::Vector3d halfKick = 0.5 * step_.h * settings_.gravity;
  for (const IslandWork& island : step_.work)
    if (island.symmetricStep)
      for (const std::int32_t i : island.island.bodies)
        if (state_.isDynamic(i)) state_.linearVelocities[i] += halfKick;
  joints_.projectVelocities(state_, step_.symmetricJoints);
}

void World::projectJointIslandEnergies() {
  if (step_.startEnergies.empty() || !report_.joints.correctionConverged) return;
  for (const IslandWork& island : step_.work) {
    if (!island.items[kContactRows].empty() || !island.items[kTreeRows].empty()) continue;
    if (island.outcome.status != solvers::SolverStatus::Converged) continue;  // rows not held
    bool anchored = false;
    double tolerance = 0.0;
    const joints::EnergyTarget energy = joints_.energyTarget(
        island.items[kJointRows], settings_.jointStabilization, state_, anchored, tolerance);
    if (energy == joints::EnergyTarget::None) continue;
    // (`exact` islands take the symmetric step, which has no first-order term to keep.)
    const double powerWeight = energy == joints::EnergyTarget::Modified ? 0.5 * step_.h : 0.0;
    // applied forces do work the projection cannot know
    if (drivenFromOutside(island.island.bodies, state_, articulations_)) continue;
    // The power term at the start of the step, with the tangent velocities of the step's start
    // where the joints give them (else the start velocities).
    const std::span<const std::int32_t> joints = island.items[kJointRows];
    std::vector<Eigen::Vector3d>& u = step_.powerVelocities;
    const bool tangent =
        powerWeight > 0.0 &&
        joints_.boundaryVelocities(joints, state_, step_.startPoses, step_.startLinearVelocities,
                                   step_.startAngularVelocities, u);
    double target = 0.0;
    for (const std::int32_t i : island.island.bodies) {
      const Eigen::Vector3d& start = tangent ? u[i] : step_.startLinearVelocities[i];
      target += step_.startEnergies[i] +
                powerWeight * settings_.gravity.dot(start) / state_.inverseMasses[i];
    }
    const bool tangentEnd =
        tangent && joints_.boundaryVelocities(joints, state_, state_.poses, state_.linearVelocities,
                                              state_.angularVelocities, u);
    // The energy is known to the joints' tolerance only: a body k joints from the anchor is within
    // k tolerances of its place, so the potential within |g| tolerance (joints) (mass).
    double mass = 0.0;
    for (const std::int32_t i : island.island.bodies) mass += 1.0 / state_.inverseMasses[i];
    const double resolution =
        settings_.gravity.norm() * tolerance * static_cast<double>(joints.size()) * mass;
    const integrators::EnergyProjection projection = integrators::projectEnergy(
        state_, island.island.bodies, anchored, target, settings_.gravity, powerWeight,
        tangentEnd ? std::span<const Eigen::Vector3d>(u) : std::span<const Eigen::Vector3d>(),
        resolution);
    if (!projection.applied) continue;
    ++report_.joints.energyProjections;
    report_.joints.largestEnergyCorrection =
        std::max(report_.joints.largestEnergyCorrection, std::abs(projection.energyError));
  }
}

}  // namespace coulomb::engine
