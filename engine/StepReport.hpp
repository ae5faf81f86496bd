#pragma once
// What one World::step did: per island, the solver used and why, the fallbacks tried, status,
// iterations, time and the common residual; plus what the collision stage found and skipped.
#include <coulomb/geometry/CollisionPipeline.hpp>
#include <coulomb/geometry/Ids.hpp>
#include <coulomb/solvers/SolvePlan.hpp>
#include <coulomb/solvers/SolverReport.hpp>

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace coulomb::engine {

struct IslandReport {
  std::int32_t island = 0;   // island id of this step (ordered by smallest body index)
  std::size_t bodies = 0;    // dynamic bodies in the island
  std::size_t contacts = 0;  // contact points (row blocks)
  int unknowns = 0;          // scalar unknowns of its problem
  int degreesOfFreedom = 0;  // m of nu = 3n/m
  // Dependent combinations of the island's joint rows (a kinematic loop's redundant rows) and the
  // velocity demand removed along them [m/s, rad/s] (docs/solver-derivations.md (10.3)).
  int redundantJointRows = 0;
  double redundantDemandRemoved = 0.0;
  solvers::SolvePlan plan;  // the attempts run for it, the chooser's rule and features
  // Converged when the applied answer is within the policy's tolerance (solveWithFallback);
  // else the status of the attempt whose answer was applied.
  solvers::SolverStatus status = solvers::SolverStatus::NotApplicable;
  solvers::SolverReport solve;  // report of the attempt whose answer was applied (own status)
  std::vector<solvers::SolverReport> attempts;  // every attempt, in order (fallbacks = size - 1)
  std::optional<solvers::SolverReport> penetration;  // split impulse's pseudo-solve, if it ran
  double penetrationSeconds = 0.0;                   // [s] split-impulse correction

  /// Why this plan (formatted on each call: the step itself formats nothing). An island solved by
  /// its groups of acting contacts (solvers/ActiveGroups.hpp) says so first: its plan is the one
  /// that would have run had the groups' answer missed the tolerance.
  [[nodiscard]] std::string reason() const {
    if (solve.solver == "groups")
      return "solved by its groups of acting contacts (" + solve.message +
             ", each by its own automatic plan); the island's plan, not run: " + plan.reason();
    return plan.reason();
  }
  [[nodiscard]] bool converged() const { return status == solvers::SolverStatus::Converged; }
};

/// What the joints did in one step (all islands together).
struct JointStepReport {
  std::size_t joints = 0;        // active joints (live, unbroken)
  double maxLinearError = 0.0;   // [m] largest anchor gap / slider offset after the step
  double maxAngularError = 0.0;  // [-, ~rad] largest axis misalignment after the step
  int correctionIterations = 0;  // predicted-state correction solves
  double correctionError = 0.0;  // [m or rad] largest predicted error left by the correction
  bool correctionConverged = true;
  double correctionSeconds = 0.0;         // [s] wall clock of the correction
  int energyProjections = 0;              // islands of ideal joints projected to their energy
  double largestEnergyCorrection = 0.0;   // [J] largest |energy restored| by one projection
  std::vector<geometry::JointId> broken;  // joints that broke in this step
};

/// A body (or articulation) the World-level guard isolated in this step (engine/Quarantine.hpp).
struct QuarantineEvent {
  geometry::BodyId body;                  // invalid for an articulation
  geometry::ArticulationId articulation;  // invalid for a free body
  std::string name;                       // the body's or the articulation's name
  std::string reason;  // e.g. "non-finite velocity after the velocity prediction"
};

struct StepReport {
  std::uint64_t stepIndex = 0;    // index of this step (0 for the first)
  double timeStep = 0.0;          // [s] h used
  double time = 0.0;              // [s] simulated time at the end of the step
  std::size_t dynamicBodies = 0;  // bodies integrated under forces
  std::size_t kinematicBodies = 0;
  std::size_t sleepingBodies = 0;  // dynamic bodies asleep at the end of the step (engine/Sleep)
  geometry::CollisionStats collision;                         // pairs, manifolds, points
  std::vector<geometry::CollisionFailure> collisionFailures;  // pairs skipped this step
  std::vector<IslandReport> islands;
  JointStepReport joints;                    // drift, predicted-state correction, breakage
  std::vector<QuarantineEvent> quarantined;  // bodies and trees isolated in this step
  // What a user must hear about, each said once per World (in the step where it first happens):
  // e.g. a solver forced on an island it cannot take (NAME!: no fallback), whose contacts then
  // get no impulse. The CLI prints them on stderr; the library prints nothing.
  std::vector<std::string> warnings;
  double seconds = 0.0;  // [s] wall clock of the whole step
  // [s] wall clock of the stages WorldSettings::threads spreads over its threads: the islands'
  // rows, solves and impulses, the split impulse, and the trees' velocity prediction and
  // integration (docs/embedding.md, "Threads"). The rest of `seconds` runs on the calling thread.
  double islandStageSeconds = 0.0;
  double penetrationStageSeconds = 0.0;
  double treeStageSeconds = 0.0;
  int threads = 1;  // the threads the step ran on (World::threads())

  [[nodiscard]] std::size_t fallbacks() const {
    std::size_t n = 0;
    for (const IslandReport& i : islands) n += i.attempts.empty() ? 0 : i.attempts.size() - 1;
    return n;
  }
};

}  // namespace coulomb::engine
