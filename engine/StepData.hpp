#pragma once
// The data one World::step passes from stage to stage (docs/architecture.md, "The step"): the
// constraint edges tagged by their row source, the islands, and per island its rows (one range
// per source), its problem, plan and outcome. Every stage reads and writes these fields and
// nothing set aside elsewhere; World keeps one StepData and reuses it, so its vectors keep their
// capacity from step to step.
#include <coulomb/engine/IslandBuilder.hpp>
#include <coulomb/engine/JointLoops.hpp>
#include <coulomb/engine/PenetrationCorrection.hpp>
#include <coulomb/engine/ProblemAssembler.hpp>
#include <coulomb/engine/RowSource.hpp>
#include <coulomb/geometry/Pose.hpp>
#include <coulomb/joints/RowSet.hpp>
#include <coulomb/solvers/RedundantRows.hpp>
#include <coulomb/solvers/SolvePlan.hpp>
#include <coulomb/solvers/SolveWithFallback.hpp>

#include <array>
#include <cstdint>
#include <optional>
#include <vector>

namespace coulomb::engine {

/// The row sources of a step, in the order their blocks appear in an island's rows (joints
/// first, then contacts, then tree rows: the order every solver sweeps them in).
enum RowOwner : std::uint8_t { kJointRows = 0, kContactRows = 1, kTreeRows = 2, kRowOwners = 3 };

/// One island through the step.
struct IslandWork {
  Island island;                                            // bodies and edges (ascending)
  std::array<std::vector<std::int32_t>, kRowOwners> items;  // per source: its items, ascending
  joints::RowSet rows;                                      // every source's blocks
  std::array<joints::BlockRange, kRowOwners> blocks;        // per source: where its blocks are
  AssembledProblem assembled;                               // W, q, slots
  bool automaticPlan = true;                                // the policy's choice was Automatic
  solvers::SolvePlan plan;
  solvers::PlanOutcome outcome;
  // This island's solvers (the plan's and the split impulse's), kept with the island slot: their
  // workspaces stay sized to the island found in this slot step after step, so a steady step
  // resizes none of them, and islands never share a solver (independent solves).
  solvers::SolverInstances solvers;
  solvers::UnionFind groupScratch;  // solvers::splitsByActingContacts's, kept for its storage
  // Redundant joint rows (a loop's): the demand removed along them this step, and the storage
  // of the search (engine/JointLoops.hpp, solvers/RedundantRows.hpp).
  solvers::RedundantDemand redundant;
  solvers::RedundantRowsWorkspace redundantRows;
  JointLoopScratch loopScratch;
  std::optional<solvers::SolverReport> penetration;  // the split impulse's pseudo-solve
  bool penetrates = false;  // a contact beyond the slop: the split impulse has work this step
  // An island of ideal joints that keeps its exact energy, with nothing else acting: its bodies
  // take half of the step's gravity kick before the solve and half after the position update
  // (the symmetric step; World::splitJointIslandKicks).
  bool symmetricStep = false;
  double penetrationSeconds = 0.0;
  VelocityProblemNormals penetrationNormals;  // the split impulse's view of W (kept for storage)

  [[nodiscard]] const std::vector<std::int32_t>& itemsOf(RowOwner owner) const {
    return items[owner];
  }
};

struct StepData {
  double h = 0.0;
  StepEdges edges;                            // every source's edges, tagged
  std::vector<std::uint8_t> dynamicMask;      // per body slot: carries unknowns in this step
  std::vector<Island> islands;                // from the island builder
  std::vector<IslandWork> work;               // one per island, same order
  std::vector<std::int32_t> activeJoints;     // joint slots with an edge this step
  std::vector<std::int32_t> symmetricJoints;  // the joints of the islands with symmetricStep
  // The world inverse inertias of the velocity solve when some differ from the bodies' own
  // (JointStage::stabilizedInverseInertias); unused when `stabilized` is false.
  bool stabilized = false;
  InverseInertias solveInverseInertias;
  // Per body slot: its energy at the step's start (integrators/EnergyProjection.hpp), recorded
  // when the world has joints; empty otherwise.
  std::vector<double> startEnergies;
  std::vector<geometry::Pose> startPoses;  // the same bodies' poses
  // Every body's velocities at the step's start (v_k), for ContactProblem::stepQ and the energy
  // projection.
  std::vector<Eigen::Vector3d> startLinearVelocities, startAngularVelocities;
  std::vector<Eigen::Vector3d> powerVelocities;  // scratch of the energy projection

  [[nodiscard]] const InverseInertias* inverseInertias() const {
    return stabilized ? &solveInverseInertias : nullptr;
  }
};

}  // namespace coulomb::engine
