// `coulomb run`, `coulomb scenes` and `coulomb demo` (docs/architecture.md section 0).
#include <coulomb/engine/World.hpp>
#include <coulomb/io/Snapshot.hpp>

#include <cstdio>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>

#include "Commands.hpp"
#include "FreeFlightSamples.hpp"
#include "ProblemCapture.hpp"
#include "RunOutputs.hpp"
#include "SceneRun.hpp"
#include "scenes/SceneRegistry.hpp"

namespace coulomb::cli {
namespace {

struct RunOptions {
  std::string scene;
  SceneOverrides overrides;
  std::string trajectoryPath;
  std::string statsPath;
  std::string contactsPath;
  std::string captureDirectory;
  std::optional<std::uint64_t> captureStep;
  std::string loadSnapshotPath;  // restored into the scene's world before the first step
  std::string saveSnapshotPath;  // written after the last step
};

void writeTrajectoryRows(std::ostream& out, const engine::World& world) {
  const geometry::BodyState& s = world.state();
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (s.alive[i] == 0 || s.motionTypes[i] == geometry::MotionType::Static) continue;
    const auto& p = s.poses[i];
    const auto& v = s.linearVelocities[i];
    const auto& w = s.angularVelocities[i];
    out << world.time() << ',' << i << ',' << world.name(world.idAt(i)) << ',' << p.position.x()
        << ',' << p.position.y() << ',' << p.position.z() << ',' << p.rotation.w() << ','
        << p.rotation.x() << ',' << p.rotation.y() << ',' << p.rotation.z() << ',' << v.x() << ','
        << v.y() << ',' << v.z() << ',' << w.x() << ',' << w.y() << ',' << w.z() << '\n';
  }
}

struct Totals {
  double kineticEnergy = 0.0;
  Eigen::Vector3d angularMomentum = Eigen::Vector3d::Zero();  // about the world origin
};

Totals totals(const geometry::BodyState& s) {
  Totals t;
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (!s.isDynamic(i)) continue;
    t.kineticEnergy += s.kineticEnergy(i);
    const double mass = 1.0 / s.inverseMasses[i];
    t.angularMomentum +=
        s.angularMomentum(i) + s.poses[i].position.cross(mass * s.linearVelocities[i]);
  }
  return t;
}

std::string jsonVector(const Eigen::Vector3d& v) {
  std::ostringstream out;
  out << std::setprecision(17) << '[' << v.x() << ", " << v.y() << ", " << v.z() << ']';
  return out.str();
}

void run(const RunOptions& options) {
  const engine::io::Scene scene = loadScene(options.scene, options.overrides);
  engine::World world = buildWorldFor(scene);
  if (!options.loadSnapshotPath.empty()) {  // the same scene, continued (io/Snapshot.hpp)
    engine::io::loadSnapshotFile(world, options.loadSnapshotPath);
    // The snapshot brings the settings it was saved with; what this command line sets for the
    // solve (solver, tolerance, iteration cap, threads) applies to the continuation, so that one
    // saved state can be continued with each solver.
    engine::WorldSettings settings = world.settings();
    const SceneOverrides& o = options.overrides;
    if (o.solver) settings.solve.choice = scene.settings.solve.choice;
    if (o.tolerance) settings.solve.options.tolerance = scene.settings.solve.options.tolerance;
    if (o.maxIterations)
      settings.solve.options.maxIterations = scene.settings.solve.options.maxIterations;
    if (o.threads) settings.threads = scene.settings.threads;
    world.setSettings(settings);
  }

  std::optional<std::ofstream> trajectory;
  if (!options.trajectoryPath.empty()) {
    trajectory = openOutputFile(options.trajectoryPath, "trajectory");
    *trajectory << "time,body,name,x,y,z,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz\n";
    writeTrajectoryRows(*trajectory, world);
  }
  std::optional<ContactsCsv> contacts;
  if (!options.contactsPath.empty()) contacts.emplace(options.contactsPath);
  std::optional<StatsJson> stats;
  if (!options.statsPath.empty()) stats.emplace(options.statsPath);
  std::optional<ProblemCapture> capture;
  if (!options.captureDirectory.empty()) {
    capture.emplace(options.captureDirectory, scene.name, options.captureStep);
    capture->attach(world);
  }

  const Totals initial = totals(world.state());
  RunMetrics metrics(world);
  runSteps(world, scene.steps, scene.settings.timeStep, metrics,
           [&](const engine::StepReport& report) {
             if (trajectory) writeTrajectoryRows(*trajectory, world);
             if (contacts) contacts->write(world, report);
             if (stats) stats->writeStep(report, report.seconds);
           });
  if (capture) capture->throwIfFailed();
  if (!options.saveSnapshotPath.empty())
    engine::io::saveSnapshotFile(world, options.saveSnapshotPath);
  const Totals final = totals(world.state());
  char hash[32];
  std::snprintf(hash, sizeof hash, "%016llx", static_cast<unsigned long long>(world.stateHash()));
  const double meanStepSeconds = 1e-3 * metrics.meanStepMilliseconds();
  const double stepSeconds = meanStepSeconds * static_cast<double>(metrics.steps());

  std::cout << "scene " << scene.name << " (" << scene.source << "): " << world.bodyCount()
            << (world.bodyCount() == 1 ? " body, " : " bodies, ") << metrics.steps() << " steps of "
            << scene.settings.timeStep << " s, solver " << scene.settings.solve.choice.text()
            << "\n"
            << "  simulated " << world.time() << " s in " << stepSeconds << " s ("
            << meanStepSeconds * 1e6 << " us/step mean, " << metrics.medianStepMilliseconds() * 1e3
            << " us/step median)\n"
            << "  kinetic energy " << initial.kineticEnergy << " -> " << final.kineticEnergy
            << " J\n"
            << "  state hash " << hash << "\n";
  if (!options.loadSnapshotPath.empty())
    std::cout << "  continued from snapshot " << options.loadSnapshotPath << "\n";
  if (!options.saveSnapshotPath.empty())
    std::cout << "  snapshot of step " << world.stepCount() << " saved to "
              << options.saveSnapshotPath << "\n";
  if (metrics.diverged())
    std::cout << "  DIVERGED at t=" << world.time() << " s (non-finite, or beyond 1000 m or m/s)\n";
  if (metrics.collisionFailures() > 0)
    std::cout << "  collision: " << metrics.collisionFailures() << " pair failures skipped\n";
  if (stats) {
    printSolverSummary(std::cout, metrics);
    std::ostringstream extra;
    extra << std::setprecision(17) << "  \"step_seconds_total\": " << stepSeconds
          << ",\n  \"step_seconds_mean\": " << meanStepSeconds
          << ",\n  \"kinetic_energy\": {\"initial\": " << initial.kineticEnergy
          << ", \"final\": " << final.kineticEnergy << "}"
          << ",\n  \"angular_momentum\": {\"initial\": " << jsonVector(initial.angularMomentum)
          << ", \"final\": " << jsonVector(final.angularMomentum) << "}"
          << ",\n  \"state_hash\": \"" << hash << "\"";
    stats->finish(scene, world, metrics, extra.str());
  }
  if (capture)
    std::cout << "  captured " << capture->filesWritten() << " island problems in "
              << options.captureDirectory << " (" << capture->islandsSkipped()
              << " skipped: rows without an fc3d form)\n";
}

void listScenes() {
  for (const scenes::BuiltinScene& s : scenes::builtinScenes()) {
    const engine::io::Scene scene = scenes::loadBuiltinScene(s.name);
    std::cout << std::left << std::setw(16) << s.name << " " << scene.description << "\n";
  }
}

}  // namespace

void registerSceneCommands(CLI::App& app) {
  auto options = std::make_shared<RunOptions>();
  CLI::App* runCommand =
      app.add_subcommand("run", "Run a scene (built-in name, JSON file or URDF robot)");
  runCommand
      ->add_option(
          "scene", options->scene,
          "Built-in scene name, path to a .json scene or a .urdf robot (placed on a floor)")
      ->required();
  runCommand->add_flag("--floating", options->overrides.urdfFloating,
                       "A .urdf robot gets a floating base (default: fixed)");
  runCommand->add_flag("--limp", options->overrides.urdfLimp,
                       "A .urdf robot's joints are not held by motors (default: held)");
  runCommand->add_flag("--maximal", options->overrides.urdfMaximal,
                       "A .urdf robot as free bodies and maximal joints (needs --limp)");
  runCommand->add_option("--threads", options->overrides.threads,
                         "Threads of each step: a count or hardware (default: the scene's, 1); "
                         "results are bit-identical whatever the count (docs/embedding.md)");
  runCommand->add_option("--solver", options->overrides.solver,
                         "Contact solver of every island: auto, a name of `coulomb solvers`, "
                         "NAME! (no fallback) or a chain a,b,c (default: the scene's)");
  runCommand->add_option("--dt", options->overrides.timeStep,
                         "Time step [s] (default: the scene's)");
  runCommand
      ->add_option("--steps", options->overrides.steps, "Number of steps (default: the scene's)")
      ->check(CLI::PositiveNumber);
  runCommand->add_option("--mu", options->overrides.friction,
                         "Friction coefficient of every material of the scene (every shape of "
                         "every body and link; default: the scene's)");
  runCommand->add_option("--joint-energy", options->overrides.jointEnergy,
                         "Energy target of every joint under the predicted-state policy: none, "
                         "modified or exact (exact: the symmetric step, E never rises; "
                         "docs/tuning.md \"Chains keep their energy\"; default: the scene's)");
  runCommand->add_option("--out", options->trajectoryPath,
                         "Write every moving body's state at every step as CSV");
  runCommand->add_option("--stats", options->statsPath,
                         "Write per-step, per-island solver data and the run's summary as JSON, "
                         "and print a per-solver summary");
  runCommand->add_option("--contacts", options->contactsPath,
                         "Write every contact point of every step as CSV");
  runCommand->add_option("--capture", options->captureDirectory,
                         "Write each island's contact problem as .fc3d into this folder "
                         "(replay with `coulomb solve`)");
  runCommand
      ->add_option("--capture-step", options->captureStep,
                   "Capture only this step (0 = the first; default: every step)")
      ->needs("--capture");
  runCommand->add_option("--load-snapshot", options->loadSnapshotPath,
                         "Continue from this snapshot (saved by --save-snapshot from the same "
                         "scene) for --steps more steps; --solver, --tol, --max-iter and "
                         "--threads given here replace the snapshot's");
  runCommand->add_option("--save-snapshot", options->saveSnapshotPath,
                         "Save the whole state after the last step (binary, versioned)");
  runCommand->callback([options] { run(*options); });

  app.add_subcommand("scenes", "List the built-in scenes")->callback(listScenes);

  app.add_subcommand("demo", "Run the free-flight samples and print what they measure")
      ->callback([] {
        if (!samples::runFreeFlightDemo(std::cout))
          throw CommandError("a free-flight measurement is outside its expected bound");
      });
}

}  // namespace coulomb::cli
