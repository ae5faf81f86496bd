#include "RunOutputs.hpp"

#include <coulomb/solvers/SolverReport.hpp>

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <iomanip>

#include "Commands.hpp"

namespace coulomb::cli {
namespace {

nlohmann::json finiteOrNull(double value) {
  return std::isfinite(value) ? nlohmann::json(value) : nlohmann::json(nullptr);
}

nlohmann::json attemptJson(const solvers::SolverReport& r) {
  nlohmann::json attempt = {{"solver", r.solver},
                            {"status", solvers::statusName(r.status)},
                            {"iterations", r.iterations},
                            {"seconds", r.seconds},
                            {"residual", finiteOrNull(r.residual)}};
  if (!r.message.empty()) attempt["note"] = r.message;  // e.g. "sticking start", a stall
  return attempt;
}

nlohmann::json islandJson(const engine::IslandReport& island) {
  nlohmann::json attempts = nlohmann::json::array();
  for (const solvers::SolverReport& a : island.attempts) attempts.push_back(attemptJson(a));
  nlohmann::json out = {{"island", island.island},
                        {"bodies", island.bodies},
                        {"contacts", island.contacts},
                        {"unknowns", island.unknowns},
                        {"degrees_of_freedom", island.degreesOfFreedom},
                        {"solver", island.solve.solver},
                        {"reason", island.reason()},
                        {"status", solvers::statusName(island.status)},
                        {"iterations", island.solve.iterations},
                        {"seconds", island.solve.seconds},
                        {"residual", finiteOrNull(island.solve.residual)},
                        {"fallbacks", island.attempts.empty() ? 0 : island.attempts.size() - 1},
                        {"penetration_seconds", island.penetrationSeconds},
                        {"attempts", attempts}};
  if (island.redundantJointRows > 0) {  // a loop's dependent joint rows (docs/solvers.md)
    out["redundant_joint_rows"] = island.redundantJointRows;
    out["redundant_demand_removed"] = island.redundantDemandRemoved;
  }
  return out;
}

nlohmann::json tallyJson(const SolverTally& t, std::uint64_t steps) {
  return {
      {"islands", t.islands},
      {"iterations_mean", t.meanIterations()},
      {"iterations_max", t.iterationsMax},
      {"residual_mean", t.meanResidual()},
      {"residual_max", t.residualMax},
      {"fallbacks", t.fallbacks},
      {"unconverged", t.unconverged},
      {"solve_ms_per_step", steps > 0 ? 1e3 * t.solveSeconds / static_cast<double>(steps) : 0.0}};
}

}  // namespace

std::ofstream openOutputFile(const std::string& path, const char* what) {
  std::ofstream out(path);
  if (!out) throw CommandError("cannot write the " + std::string(what) + " file '" + path + "'");
  out << std::setprecision(17);
  return out;
}

ContactsCsv::ContactsCsv(const std::string& path) : out_(openOutputFile(path, "contacts")) {
  out_ << "step,time,body_a,name_a,body_b,name_b,x,y,z,nx,ny,nz,depth,normal_impulse,"
          "tangent_impulse_1,tangent_impulse_2\n";
}

void ContactsCsv::write(const engine::World& world, const engine::StepReport& report) {
  for (const geometry::ContactManifold& m : world.contacts()) {
    const std::string& nameA = world.contains(m.bodyA) ? world.name(m.bodyA) : std::string();
    const std::string& nameB = world.contains(m.bodyB) ? world.name(m.bodyB) : std::string();
    for (const geometry::ContactPoint& p : m.activePoints()) {
      out_ << report.stepIndex << ',' << report.time << ',' << m.bodyA.index << ',' << nameA << ','
           << m.bodyB.index << ',' << nameB << ',' << p.position.x() << ',' << p.position.y() << ','
           << p.position.z() << ',' << m.normal.x() << ',' << m.normal.y() << ',' << m.normal.z()
           << ',' << p.depth << ',' << p.normalImpulse << ',' << p.tangentImpulse.x() << ','
           << p.tangentImpulse.y() << '\n';
    }
  }
  if (!out_) throw CommandError("writing the contacts file failed");
}

StatsJson::StatsJson(const std::string& path) : out_(openOutputFile(path, "stats")) {
  out_ << "{\n  \"per_step\": [";
}

void StatsJson::writeStep(const engine::StepReport& report, double stepSeconds) {
  nlohmann::json islands = nlohmann::json::array();
  for (const engine::IslandReport& island : report.islands) islands.push_back(islandJson(island));
  const nlohmann::json step = {{"step", report.stepIndex},
                               {"time", report.time},
                               {"seconds", stepSeconds},
                               {"candidate_pairs", report.collision.candidatePairs},
                               {"manifolds", report.collision.touchingPairs},
                               {"contact_points", report.collision.contactPoints},
                               {"collision_failures", report.collisionFailures.size()},
                               {"fallbacks", report.fallbacks()},
                               {"islands", islands},
                               {"joints",
                                {{"count", report.joints.joints},
                                 {"max_linear_error", report.joints.maxLinearError},
                                 {"max_angular_error", report.joints.maxAngularError},
                                 {"correction_iterations", report.joints.correctionIterations},
                                 {"correction_error", report.joints.correctionError},
                                 {"correction_converged", report.joints.correctionConverged},
                                 {"energy_projections", report.joints.energyProjections},
                                 {"energy_restored", report.joints.largestEnergyCorrection}}}};
  out_ << (firstStep_ ? "\n    " : ",\n    ") << step.dump();
  firstStep_ = false;
}

void StatsJson::finish(const engine::io::Scene& scene, const engine::World& world,
                       const RunMetrics& metrics, const std::string& extraMembers) {
  nlohmann::json perSolver = nlohmann::json::object();
  for (const auto& [name, tally] : metrics.solvers())
    perSolver[name] = tallyJson(tally, metrics.steps());
  const nlohmann::json summary = {
      {"scene", scene.name},
      {"source", scene.source},
      {"solver", scene.settings.solve.choice.text()},
      {"bodies", world.bodyCount()},
      {"steps", metrics.steps()},
      {"time_step", scene.settings.timeStep},
      {"simulated_time", world.time()},
      {"ms_per_step_median", metrics.medianStepMilliseconds()},
      {"ms_per_step_mean", metrics.meanStepMilliseconds()},
      {"solvers", perSolver},
      {"all_islands", tallyJson(metrics.allSolvers(), metrics.steps())},
      {"max_penetration", metrics.maxPenetration()},
      {"max_drift", metrics.maxDrift()},
      {"joints",
       {{"max_linear_error", metrics.maxJointGap()},
        {"max_angular_error", metrics.maxJointAngle()},
        {"correction_failures", metrics.jointCorrectionFailures()}}},
      {"max_contact_points", metrics.maxContactPoints()},
      {"collision_failures", metrics.collisionFailures()},
      {"diverged", metrics.diverged()},
      {"energy",
       {{"initial", finiteOrNull(metrics.initialEnergy())},
        {"final", finiteOrNull(metrics.finalEnergy())},
        {"max_step_increase", finiteOrNull(metrics.maxEnergyIncrease())}}}};
  std::string members = summary.dump(2);  // "{\n  ...\n}": splice its members after per_step
  members = members.substr(1, members.size() - 2);
  while (!members.empty() && members.back() == '\n') members.pop_back();
  out_ << (firstStep_ ? "]" : "\n  ]") << "," << members;
  if (!extraMembers.empty()) out_ << ",\n" << extraMembers;
  out_ << "\n}\n";
  out_.flush();
  if (!out_) throw CommandError("writing the stats file failed");
}

void printSolverSummary(std::ostream& out, const RunMetrics& metrics) {
  const std::uint64_t steps = metrics.steps();
  char line[256];
  std::snprintf(line, sizeof line, "  %-12s %8s %9s %6s %10s %10s %9s %11s %10s\n", "solver",
                "islands", "iter_mean", "max", "res_mean", "res_max", "fallbacks", "unconverged",
                "solve_ms");
  out << line;
  for (const auto& [name, t] : metrics.solvers()) {
    std::snprintf(line, sizeof line, "  %-12s %8llu %9.2f %6d %10.2e %10.2e %9llu %11llu %10.4f\n",
                  name.empty() ? "(none)" : name.c_str(),
                  static_cast<unsigned long long>(t.islands), t.meanIterations(), t.iterationsMax,
                  t.meanResidual(), t.residualMax, static_cast<unsigned long long>(t.fallbacks),
                  static_cast<unsigned long long>(t.unconverged),
                  steps > 0 ? 1e3 * t.solveSeconds / static_cast<double>(steps) : 0.0);
    out << line;
  }
  if (metrics.solvers().empty()) out << "  (no island was solved: no contacts)\n";
  std::snprintf(line, sizeof line,
                "  ms/step %.4f (median after warm-up), %.4f (mean); max penetration %.3g m, "
                "max drift %.3g m\n",
                metrics.medianStepMilliseconds(), metrics.meanStepMilliseconds(),
                metrics.maxPenetration(), metrics.maxDrift());
  out << line;
  if (metrics.maxJointGap() > 0.0 || metrics.maxJointAngle() > 0.0) {
    std::snprintf(line, sizeof line,
                  "  joints: max gap %.3g m, max misalignment %.3g rad, %llu steps with an "
                  "unconverged drift correction\n",
                  metrics.maxJointGap(), metrics.maxJointAngle(),
                  static_cast<unsigned long long>(metrics.jointCorrectionFailures()));
    out << line;
  }
}

}  // namespace coulomb::cli
