// World::step and its stages: the data flow of docs/architecture.md, "The step". Every stage
// reads and writes step_ (StepData.hpp) and the World's state; the order below is the order of
// the step, and no stage relies on a value another stage set aside.
#include <coulomb/engine/CoulombError.hpp>
#include <coulomb/engine/ImpactPropagation.hpp>
#include <coulomb/engine/ImpulseApplier.hpp>
#include <coulomb/engine/PenetrationCorrection.hpp>
#include <coulomb/engine/World.hpp>
#include <coulomb/integrators/FreeMotion.hpp>
#include <coulomb/integrators/PositionUpdate.hpp>
#include <coulomb/solvers/ActiveGroups.hpp>
#include <coulomb/solvers/SolverChooser.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <optional>
#include <sstream>

namespace coulomb::engine {

namespace {

double secondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// The free bodies' prediction and integration in fixed ranges on the World's threads: each body
// is integrated on its own, so the results do not depend on the count. 256 bodies (~50 us of
// rotations) per task keep the hand-over small against the work.
constexpr std::size_t kBodiesPerTask = 256;

template <class Range>
void forBodyRanges(StepExecutor& executor, std::size_t bodies, Range&& range) {
  executor.forEach((bodies + kBodiesPerTask - 1) / kBodiesPerTask, [&](std::size_t k) {
    range(k * kBodiesPerTask, std::min(bodies, (k + 1) * kBodiesPerTask));
  });
}

}  // namespace

const StepReport& World::step(double h) {
  if (!std::isfinite(h) || h <= 0.0)
    throw CoulombError("step: h must be finite and > 0 s (got " + std::to_string(h) + ")");
  const auto started = std::chrono::steady_clock::now();
  resetReport(h);
  StepReport& report = report_;
  for (std::size_t i = 0; i < state_.size(); ++i) {
    if (state_.isDynamic(i)) ++report.dynamicBodies;
    if (state_.alive[i] != 0 && state_.motionTypes[i] == geometry::MotionType::Kinematic)
      ++report.kinematicBodies;
  }
  step_.h = h;

  quarantine_.begin(state_, articulations_);  // last good state
  recordStartEnergies();                      // E~ at the start, for the energy projection
  step_.startLinearVelocities = state_.linearVelocities;  // v_k (the vectors keep their storage)
  step_.startAngularVelocities = state_.angularVelocities;
  forBodyRanges(executor_, state_.size(), [&](std::size_t first, std::size_t last) {  // v*
    integrators::predictFreeVelocities(state_, settings_.gravity, h, first, last);
  });
  // Stage clocks are read only around stages that have work: a read costs ~25 ns, a tenth of a
  // one-body step.
  const bool trees = articulations_.count() > 0;
  auto treesStarted = trees ? std::chrono::steady_clock::now() : started;
  articulations_.predictVelocities(settings_.gravity, h, state_, executor_);  // trees' v* (ABA)
  if (trees) report.treeStageSeconds = secondsSince(treesStarted);
  guard("after the velocity prediction", report);  // bad v*
  detectContacts(h);  // manifolds, margins swept by v*; touched sleepers wake
  modifyContacts();   // the user's pre-solve hook: friction, restitution, surface speed, off
  buildIslands();     // edges of every row source -> islands with per-source item lists
  step_.stabilized =  // heavy joint loads: the velocity solve's inertias (as data)
      joints_.stabilizedInverseInertias(state_, h, step_.solveInverseInertias);
  splitJointIslandKicks();  // islands keeping the exact energy: half the kick now, half at the end
  const auto islandsStarted = std::chrono::steady_clock::now();
  executor_.forEach(step_.work.size(), [this](std::size_t k) {  // v* -> v+, island by island
    IslandWork& island = step_.work[k];  // (each writes its own bodies, rows and points only)
    emitRows(island);       // impacts (propagating law), then joint, contact and tree rows
    solveIsland(island);    // W = J M^-1 J^T, q = J v*; the policy's plan; the outcome
    applyImpulses(island);  // v+ = v* + M^-1 J^T r, qd+; each source keeps its impulses
  });
  report.islandStageSeconds = secondsSince(islandsStarted);
  reportIslands();  // the problem observer, unsolved islands' warnings (in island order)
  joints_.correctDrift(state_, step_.activeJoints, settings_.jointStabilization, h,
                       report.joints);  // predicted state
  forBodyRanges(executor_, state_.size(), [&](std::size_t first, std::size_t last) {
    integrators::integratePositions(state_, h, first, last);  // x+ from v+
  });
  if (trees) treesStarted = std::chrono::steady_clock::now();
  articulations_.integratePositions(h, settings_.treeIntegrator, state_,
                                    executor_);  // q+ from qd+; link proxies follow
  if (trees) report.treeStageSeconds += secondsSince(treesStarted);
  collision_.clampContinuous(colliders_, state_, h);  // continuous bodies stop at first touch
  correctPenetrations();         // split impulse (positions only); its stage time in the report
  finishJointIslandKicks();      // islands of ideal joints: the second half kick, J(x+) v+ = 0
  projectJointIslandEnergies();  // islands of ideal joints keep their E~ (chains, pendulums)
  joints_.finishStep(state_, step_.activeJoints, h, report.joints);   // reactions, breakage
  sleep_.update(step_.islands, state_, settings_.sleep, h);           // slow islands fall asleep
  events_.update(collision_.cache().manifolds(), colliders_, state_,  // begin / persist / end
                 settings_.contact.touchingTolerance);
  report.islands.resize(step_.work.size());
  for (std::size_t k = 0; k < step_.work.size(); ++k)
    fillIslandReport(step_.work[k], report.islands[k]);
  guard("at the end of the step", report);  // non-finite or runaway bodies

  state_.clearForces();
  articulations_.clearForces();
  report.collision = collision_.diagnostics().stats;
  report.collisionFailures.assign(collision_.diagnostics().failures.begin(),
                                  collision_.diagnostics().failures.end());
  report.sleepingBodies = sleep_.sleepingBodies(state_);
  ++stepCount_;
  time_ += h;
  report.time = time_;
  report.seconds = secondsSince(started);
  return report;
}

RowContext World::rowContext() {
  return RowContext{state_, step_.h, collision_.cache().manifolds(), settings_.contact,
                    settings_.jointStabilization};
}

RowSource& World::rowSource(RowOwner owner) {
  switch (owner) {
    case kJointRows:
      return joints_;
    case kContactRows:
      return contactRows_;
    default:
      return articulations_;
  }
}

void World::detectContacts(double h) {
  const geometry::SweepMotion sweep{state_.linearVelocities, state_.angularVelocities, h};
  collision_.step(
      colliders_, state_.poses, sweep,
      [this](const auto& a, const auto& b) {
        if (a.sensor && b.sensor) return false;
        const std::uint32_t i = a.body.index, j = b.body.index;
        if (!articulations_.keepPair(i, j)) return false;
        if (quarantine_.isolated(i) || quarantine_.isolated(j)) return false;
        // A pair is looked at when something in it can move: an awake body, a tree's link, or a
        // moving kinematic body against a sleeping one (which it wakes).
        const bool moves = state_.isDynamic(i) || state_.isDynamic(j) || articulations_.isLink(i) ||
                           articulations_.isLink(j) ||
                           (state_.asleep[j] != 0 && state_.isMovingKinematic(i)) ||
                           (state_.asleep[i] != 0 && state_.isMovingKinematic(j));
        return moves && (!contactFilter_ || contactFilter_(a, b));
      },
      narrowPhaseThreads());
  sleep_.wakeTouched(collision_.cache().manifolds(), state_, settings_.gravity, h);
}

geometry::ParallelFor World::narrowPhaseThreads() {
  if (executor_.threads() == 1) return {};
  return [this](std::size_t count, geometry::TaskRef task) { executor_.forEach(count, task); };
}

void World::buildIslands() {
  const RowContext context = rowContext();
  StepEdges& edges = step_.edges;
  edges.clear();
  contactRows_.appendEdges(kContactRows, context, edges);
  joints_.appendEdges(kJointRows, context, edges);
  articulations_.appendEdges(kTreeRows, context, edges);
  articulations_.mapEdges(edges.edges);  // a tree is one unit (its root link's proxy)
  step_.activeJoints.clear();
  for (std::size_t e = 0; e < edges.edges.size(); ++e)
    if (edges.owners[e] == kJointRows) step_.activeJoints.push_back(edges.items[e]);

  step_.dynamicMask.resize(state_.size());
  for (std::size_t i = 0; i < state_.size(); ++i) step_.dynamicMask[i] = state_.isDynamic(i);
  articulations_.markIslandBodies(step_.dynamicMask);  // a tree counts once
  islandBuilder_.build(step_.dynamicMask, edges.edges, step_.islands);

  step_.work.resize(step_.islands.size());
  for (std::size_t k = 0; k < step_.islands.size(); ++k) {
    IslandWork& work = step_.work[k];
    work.island = step_.islands[k];
    for (std::vector<std::int32_t>& items : work.items) items.clear();
    for (const std::int32_t e : work.island.constraints)
      work.items[edges.owners[e]].push_back(edges.items[e]);
    work.penetration.reset();
    work.penetrationSeconds = 0.0;
    work.symmetricStep = false;  // World::splitJointIslandKicks decides
  }
}

void World::emitRows(IslandWork& island) {
  const RowContext context = rowContext();
  if (settings_.contact.impactLaw == ImpactLaw::Propagating)  // pairwise impacts change v* first
    propagateImpacts(island.items[kContactRows], context.manifolds, settings_.contact, step_.h,
                     state_);
  island.rows.blocks.clear();
  for (const RowOwner owner : {kJointRows, kContactRows, kTreeRows}) {
    const std::size_t first = island.rows.blocks.size();
    rowSource(owner).emitRows(island.items[owner], context, island.rows);
    island.blocks[owner] = {first, island.rows.blocks.size() - first};
  }
}

namespace {

// The island's J v_k, formed when its solve asks (solvers::ArrivalRowVelocities).
class IslandArrivalRows final : public solvers::ArrivalRowVelocities {
 public:
  IslandArrivalRows(const IslandWork& island, const geometry::BodyState& state,
                    const ArrivalVelocities& arrival)
      : island_(island), state_(state), arrival_(arrival) {}
  void form(Eigen::VectorXd& out) const override {
    arrivalRowVelocities(island_.rows, state_, arrival_, island_.assembled.slots, out);
  }

 private:
  const IslandWork& island_;
  const geometry::BodyState& state_;
  const ArrivalVelocities& arrival_;
};

}  // namespace

void World::solveIsland(IslandWork& island) {
  const ArrivalVelocities arrival{step_.startLinearVelocities, step_.startAngularVelocities};
  ProblemAssembler(settings_.assembly)
      .assemble(island.rows, state_, &articulations_, step_.inverseInertias(), island.assembled,
                &arrival);
  // A loop's redundant joint rows: the demand along their dependent combinations is dropped
  // (docs/solver-derivations.md (10.3)); trees and islands without joints skip the search.
  island.redundant = {};
  if (equalityRowsCloseALoop(island.rows, step_.dynamicMask, articulations_, island.loopScratch))
    island.redundant =
        solvers::removeRedundantDemands(island.assembled.problem, island.redundantRows);
  const solvers::ContactProblem& problem = island.assembled.problem;
  const solvers::SolverChoice& choice = choiceOf(island);
  island.automaticPlan = choice.isAutomatic();
  solvers::SolverChooser(settings_.solve.chooser)
      .choose(problem, {island.assembled.degreesOfFreedom}, choice, settings_.solve.options,
              island.plan);
  if (island.automaticPlan) promotion_.apply(island.island, settings_.solve.promotion, island.plan);
  island.plan.options.parallel = sweepOptions().parallel;
  // J v_k on demand (a converged solve's steady warm start) for W's entries; not for rows on
  // trees, whose links' part the assembler does not form.
  const IslandArrivalRows arrivalRows(island, state_, arrival);
  const bool lend =
      problem.W.bodySpaceOperator() == nullptr && island.assembled.scratch.treeBlocks.empty();
  island.plan.options.arrivalRows = lend ? &arrivalRows : nullptr;
  // An island whose acting contacts form several groups, linked only through contacts that do
  // not act (separating, or gaps that r = 0 keeps), is solved group by group
  // (solvers/ActiveGroups.hpp); the whole plan runs when they do not split or the whole residual
  // misses the tolerance. The contacts of one free body all share it: they never split.
  std::optional<solvers::PlanOutcome> byGroups;
  if (island.automaticPlan && island.assembled.degreesOfFreedom > 6 &&
      solvers::splitsByActingContacts(problem, island.groupScratch))
    byGroups = solvers::solveByActiveGroups(
        problem, solvers::SolverChooser(settings_.solve.chooser), choice, island.plan.options,
        registry_, nullptr, &island.solvers);
  if (byGroups)
    island.outcome = std::move(*byGroups);
  else
    solvers::solveWithFallback(problem, island.plan, registry_, island.solvers, island.outcome);
  island.plan.options.arrivalRows = nullptr;  // lent for this solve only
  promotion_.record(island.island, settings_.solve.promotion, island.automaticPlan, island.plan,
                    island.outcome);
}

solvers::SolverOptions World::sweepOptions() {
  // The sweep order is the policy's whatever the thread count (SolverOptions::parallel only lends
  // the threads): results stay the same bits for every count.
  solvers::SolverOptions options;
  options.sweepPartBlocks = settings_.solve.options.sweepPartBlocks;
  options.parallel = executor_.threads() > 1 ? &executor_ : nullptr;
  return options;
}

const solvers::SolverChoice& World::choiceOf(const IslandWork& island) const {
  // The override of the island's smallest body that has one, else the world's.
  const std::optional<solvers::SolverChoice>& own = solverOverrides_[island.island.bodies.front()];
  return own ? *own : settings_.solve.choice;
}

void World::reportIslands() {
  for (const IslandWork& island : step_.work) {
    if (problemObserver_) problemObserver_(island.island.id, island.assembled.problem);
    warnIfUnsolved(island, choiceOf(island));
  }
}

void World::warnIfUnsolved(const IslandWork& island, const solvers::SolverChoice& choice) {
  if (island.outcome.status != solvers::SolverStatus::NotApplicable ||
      island.assembled.problem.size() == 0)
    return;
  const std::string key = choice.text();
  if (std::find(warned_.begin(), warned_.end(), key) != warned_.end()) return;
  warned_.push_back(key);
  std::ostringstream s;
  s << "solver '" << key << "' cannot run on island " << island.island.id << " ("
    << island.island.bodies.size() << " bodies, " << island.blocks[kContactRows].count
    << " contacts, " << island.assembled.problem.size() << " unknowns)";
  for (const solvers::SolverReport& a : island.outcome.attempts)
    if (!a.message.empty()) s << "; " << a.solver << ": " << a.message;
  s << ". No impulse is applied there: its contacts and joints do not act. Said once; every such "
       "island has status not_applicable in the step report. Choose auto or a chain with a "
       "fallback.";
  report_.warnings.push_back(s.str());
}

void World::applyImpulses(IslandWork& island) {
  const Eigen::VectorXd& r = island.outcome.best.impulses;
  const std::vector<RowBlockSlot>& slots = island.assembled.slots;
  engine::applyImpulses(island.rows, slots, r, state_, step_.inverseInertias());   // v+
  articulations_.applyImpulses(island.assembled.scratch.trees, slots, r, state_);  // qd+
  // Kept for the next step's warm start: r, or the solve's better choice (SolveOutcome).
  const solvers::SolveOutcome& best = island.outcome.best;
  const Eigen::VectorXd& kept =
      best.hasNextWarmStart && best.nextWarmStart.size() == r.size() ? best.nextWarmStart : r;
  const RowContext context = rowContext();
  for (const RowOwner owner : {kJointRows, kContactRows, kTreeRows})
    rowSource(owner).storeImpulses(island.rows, island.blocks[owner], slots, kept, context);
}

void World::correctPenetrations() {
  // Islands without a penetration beyond the slop have nothing to do (the common step): the
  // stage is timed only when one has.
  bool any = false;
  for (IslandWork& island : step_.work) {
    island.penetrates =
        penetratesBeyondSlop(island.rows.in(island.blocks[kContactRows]),
                             collision_.cache().manifolds(), settings_.contact.penetration);
    if (!island.penetrates) {
      island.penetration.reset();  // what correctPenetration reports for nothing to do
      island.penetrationSeconds = 0.0;
    }
    any = any || island.penetrates;
  }
  if (!any) return;
  const auto started = std::chrono::steady_clock::now();
  executor_.forEach(step_.work.size(), [this](std::size_t k) {
    if (step_.work[k].penetrates) correctPenetrations(step_.work[k]);
  });
  report_.penetrationStageSeconds = secondsSince(started);
}

void World::correctPenetrations(IslandWork& island) {
  const joints::BlockRange contacts = island.blocks[kContactRows];
  const solvers::ContactSolver* solver =
      island.solvers.get(settings_.contact.penetration.solver, registry_);
  if (solver == nullptr) return;  // validated at construction; a registry only grows
  const auto started = std::chrono::steady_clock::now();
  VelocityProblemNormals& normals = island.penetrationNormals;  // kept for its storage
  normals.W = island.assembled.problem.W;
  normals.normalRows.clear();
  for (std::size_t k = contacts.first; k < contacts.end(); ++k)
    normals.normalRows.push_back(island.assembled.slots[k].offset);
  island.penetration = correctPenetration(island.rows.in(contacts), collision_.cache().manifolds(),
                                          settings_.contact.penetration, step_.h, state_, *solver,
                                          &articulations_, &normals, sweepOptions());
  normals.W = solvers::DelassusOperator();  // W's storage is the assembler's to reuse
  island.penetrationSeconds = secondsSince(started);
}

// The vectors keep their storage from the last step (islands are resized by the step and every
// field of each is overwritten), so a steady step allocates nothing here.
void World::resetReport(double h) {
  StepReport& r = report_;
  std::vector<geometry::CollisionFailure> failures = std::move(r.collisionFailures);
  std::vector<IslandReport> islands = std::move(r.islands);
  std::vector<geometry::JointId> broken = std::move(r.joints.broken);
  std::vector<QuarantineEvent> quarantined = std::move(r.quarantined);
  std::vector<std::string> warnings = std::move(r.warnings);
  r = StepReport{};  // every number and flag back to its default
  failures.clear();
  broken.clear();
  quarantined.clear();
  warnings.clear();
  r.warnings = std::move(warnings);
  r.collisionFailures = std::move(failures);
  r.islands = std::move(islands);  // resized and overwritten by the step
  r.joints.broken = std::move(broken);
  r.quarantined = std::move(quarantined);
  r.stepIndex = stepCount_;
  r.timeStep = h;
  r.threads = executor_.threads();
}

// The plan and the reports are swapped into the step report, not copied: the island's work is
// rewritten from scratch by the next step, and both sides keep their strings' and vectors'
// storage, so a steady step neither allocates nor copies them.
void World::fillIslandReport(IslandWork& island, IslandReport& report) {
  report.island = island.island.id;
  report.bodies = island.island.bodies.size();
  report.contacts = island.blocks[kContactRows].count;
  report.unknowns = island.assembled.problem.size();
  report.degreesOfFreedom = island.assembled.degreesOfFreedom;
  report.redundantJointRows = island.redundant.combinations;
  report.redundantDemandRemoved = island.redundant.removed;
  std::swap(report.plan, island.plan);
  report.status = island.outcome.status;
  std::swap(report.solve, island.outcome.best.report);
  std::swap(report.attempts, island.outcome.attempts);
  std::swap(report.penetration, island.penetration);
  report.penetrationSeconds = island.penetrationSeconds;
}

}  // namespace coulomb::engine
