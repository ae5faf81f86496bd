#pragma once
// The files `coulomb run` writes besides the trajectory: every contact point of every step
// (--contacts, CSV) and the per-step, per-island solver data with the run's summary (--stats,
// JSON), plus the per-solver summary printed on stdout.
#include <coulomb/engine/StepReport.hpp>
#include <coulomb/engine/World.hpp>
#include <coulomb/io/SceneLoader.hpp>

#include <fstream>
#include <ostream>
#include <string>

#include "SceneRun.hpp"

namespace coulomb::cli {

/// Opens `path` for writing with round-trip precision; throws CommandError naming the file.
std::ofstream openOutputFile(const std::string& path, const char* what);

/// --contacts: one row per manifold point of every step (the manifolds of that step's collision
/// stage, with the impulses the step applied):
/// step,time,body_a,name_a,body_b,name_b,x,y,z,nx,ny,nz,depth,normal_impulse,tangent_impulse_1,
/// tangent_impulse_2 (body ids are slot indices; the normal points from body a to body b).
class ContactsCsv {
 public:
  explicit ContactsCsv(const std::string& path);
  void write(const engine::World& world, const engine::StepReport& report);

 private:
  std::ofstream out_;
};

/// --stats: a JSON object whose "per_step" array holds, per step, the step's wall clock, the
/// collision counts and every island (solver, reason, status, iterations, seconds, residual,
/// attempts); the run's summary follows it (README.md, "Contacts, solver statistics and problems
/// out of a scene").
class StatsJson {
 public:
  explicit StatsJson(const std::string& path);
  void writeStep(const engine::StepReport& report, double stepSeconds);
  /// Ends the array and writes the summary fields; `extra` is written verbatim (JSON members).
  void finish(const engine::io::Scene& scene, const engine::World& world, const RunMetrics& metrics,
              const std::string& extraMembers);

 private:
  std::ofstream out_;
  bool firstStep_ = true;
};

/// Prints one line per solver: islands solved, mean/max iterations, mean/max residual,
/// fallbacks, unconverged islands and solve time per step; then ms per step (median).
void printSolverSummary(std::ostream& out, const RunMetrics& metrics);

}  // namespace coulomb::cli
