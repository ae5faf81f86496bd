#include <coulomb/engine/ImpulseApplier.hpp>
#include <coulomb/engine/PenetrationCorrection.hpp>
#include <coulomb/geometry/Quaternion.hpp>
#include <coulomb/solvers/pgs/PgsSolver.hpp>

#include <algorithm>

namespace coulomb::engine {

double baumgarteBias(const PenetrationSettings& settings, double depth, double h) {
  if (settings.method != PenetrationMethod::Baumgarte) return 0.0;
  return -settings.beta * std::max(depth - settings.slop, 0.0) / h;
}

std::optional<solvers::SolverReport> correctPenetration(
    const joints::RowSet& contactRows, const std::vector<ContactRowSource>& sources,
    const PenetrationSettings& settings, double h, geometry::BodyState& state,
    ArticulationStage* articulations) {
  if (settings.method != PenetrationMethod::SplitImpulse) return std::nullopt;
  joints::RowSet normals;
  for (std::size_t k = 0; k < contactRows.blocks.size(); ++k) {
    const double excess = sources[k].depth - settings.slop;
    const joints::RowBlock& block = contactRows.blocks[k];
    joints::RowBlock normal;
    normal.kind = joints::RowKind::Unilateral;
    normal.bodyA = block.bodyA;
    normal.bodyB = block.bodyB;
    normal.jacobianA = block.jacobianA.topRows(1);
    normal.jacobianB = block.jacobianB.topRows(1);
    // Target separation speed for the pseudo-velocity; 0 keeps touching rows non-penetrating.
    normal.bias = joints::RowVector::Constant(1, excess > 0.0 ? -settings.beta * excess / h : 0.0);
    normals.blocks.push_back(std::move(normal));
  }
  bool anyPenetration = false;
  for (const auto& b : normals.blocks) anyPenetration = anyPenetration || b.bias[0] < 0.0;
  if (!anyPenetration) return std::nullopt;

  AssembledProblem assembled = ProblemAssembler().assemble(normals, state, articulations);
  // The pseudo problem starts from zero pseudo-velocity: q is the bias alone, not J v.
  for (std::size_t k = 0; k < normals.blocks.size(); ++k)
    assembled.problem.q[assembled.slots[k].offset] = normals.blocks[k].bias[0];

  solvers::SolverOptions options;
  options.maxIterations = settings.iterations;
  options.tolerance = 1e-6;
  options.useWarmStart = false;
  const solvers::SolveOutcome outcome = solvers::PgsSolver().solve(assembled.problem, options);

  std::vector<Eigen::Vector3d> linear(state.size(), Eigen::Vector3d::Zero());
  std::vector<Eigen::Vector3d> angular(state.size(), Eigen::Vector3d::Zero());
  applyImpulsesTo(normals, assembled.slots, outcome.impulses, state, linear, angular);
  for (std::size_t i = 0; i < state.size(); ++i) {
    if (!state.isDynamic(i) || (linear[i].isZero(0.0) && angular[i].isZero(0.0))) continue;
    state.poses[i].position += h * linear[i];
    state.poses[i].rotation =
        geometry::integrateWorldRotation(state.poses[i].rotation, angular[i], h);
    state.refreshWorldInertia(i);
  }
  if (articulations != nullptr)
    articulations->applyPseudoImpulses(normals, assembled.slots, outcome.impulses, h, state);
  return outcome.report;
}

}  // namespace coulomb::engine
