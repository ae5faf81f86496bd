// `coulomb run`, `coulomb scenes` and `coulomb demo` (docs/architecture.md section 0).
#include <coulomb/engine/CoulombError.hpp>
#include <coulomb/engine/World.hpp>

#include <chrono>
#include <cstdio>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>

#include "Commands.hpp"
#include "FreeFlightSamples.hpp"
#include "scenes/SceneRegistry.hpp"

namespace coulomb::cli {
namespace {

struct RunOptions {
  std::string scene;
  std::optional<double> timeStep;
  std::optional<std::uint64_t> steps;
  std::string trajectoryPath;
  std::string statsPath;
};

std::ofstream openOutput(const std::string& path, const char* what) {
  std::ofstream out(path);
  if (!out) throw CommandError("cannot write the " + std::string(what) + " file '" + path + "'");
  out << std::setprecision(17);
  return out;
}

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

std::string jsonString(const std::string& text) {
  std::string out = "\"";
  for (const char c : text) {
    if (c == '"' || c == '\\') out += '\\';
    if (static_cast<unsigned char>(c) < 0x20) continue;
    out += c;
  }
  return out + "\"";
}

std::string jsonVector(const Eigen::Vector3d& v) {
  std::ostringstream out;
  out << std::setprecision(17) << '[' << v.x() << ", " << v.y() << ", " << v.z() << ']';
  return out.str();
}

void run(const RunOptions& options) {
  engine::io::Scene scene;
  try {
    scene = scenes::resolveScene(options.scene);
  } catch (const engine::CoulombError& e) {
    throw CommandError(e.what());
  }
  if (options.timeStep) {
    if (!std::isfinite(*options.timeStep) || *options.timeStep <= 0.0)
      throw CommandError("--dt must be finite and > 0 s");
    scene.settings.timeStep = *options.timeStep;
  }
  if (options.steps) scene.steps = *options.steps;
  engine::World world = [&] {
    try {
      return engine::io::buildWorld(scene);
    } catch (const engine::CoulombError& e) {
      throw CommandError(e.what());
    }
  }();

  std::optional<std::ofstream> trajectory;
  if (!options.trajectoryPath.empty()) {
    trajectory = openOutput(options.trajectoryPath, "trajectory");
    *trajectory << "time,body,name,x,y,z,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz\n";
    writeTrajectoryRows(*trajectory, world);
  }
  const Totals initial = totals(world.state());
  double stepSeconds = 0.0;
  for (std::uint64_t n = 0; n < scene.steps; ++n) {
    const auto start = std::chrono::steady_clock::now();
    world.step(scene.settings.timeStep);
    stepSeconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (trajectory) writeTrajectoryRows(*trajectory, world);
  }
  const Totals final = totals(world.state());
  char hash[32];
  std::snprintf(hash, sizeof hash, "%016llx", static_cast<unsigned long long>(world.stateHash()));
  const double perStep = scene.steps > 0 ? stepSeconds / static_cast<double>(scene.steps) : 0.0;

  std::cout << "scene " << scene.name << " (" << scene.source << "): " << world.bodyCount()
            << (world.bodyCount() == 1 ? " body, " : " bodies, ") << scene.steps << " steps of "
            << scene.settings.timeStep << " s\n"
            << "  simulated " << world.time() << " s in " << stepSeconds << " s (" << perStep * 1e6
            << " us/step)\n"
            << "  kinetic energy " << initial.kineticEnergy << " -> " << final.kineticEnergy
            << " J\n"
            << "  state hash " << hash << "\n";
  if (!options.statsPath.empty()) {
    std::ofstream stats = openOutput(options.statsPath, "stats");
    stats << "{\n  \"scene\": " << jsonString(scene.name)
          << ",\n  \"source\": " << jsonString(scene.source)
          << ",\n  \"bodies\": " << world.bodyCount() << ",\n  \"steps\": " << scene.steps
          << ",\n  \"time_step\": " << scene.settings.timeStep
          << ",\n  \"simulated_time\": " << world.time()
          << ",\n  \"step_seconds_total\": " << stepSeconds
          << ",\n  \"step_seconds_mean\": " << perStep
          << ",\n  \"kinetic_energy\": {\"initial\": " << initial.kineticEnergy
          << ", \"final\": " << final.kineticEnergy << "}"
          << ",\n  \"angular_momentum\": {\"initial\": " << jsonVector(initial.angularMomentum)
          << ", \"final\": " << jsonVector(final.angularMomentum) << "}"
          << ",\n  \"state_hash\": \"" << hash << "\"\n}\n";
  }
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
  CLI::App* runCommand = app.add_subcommand("run", "Run a scene (built-in name or JSON file)");
  runCommand->add_option("scene", options->scene, "Built-in scene name or path to a .json scene")
      ->required();
  runCommand->add_option("--dt", options->timeStep, "Time step [s] (default: the scene's)");
  runCommand->add_option("--steps", options->steps, "Number of steps (default: the scene's)");
  runCommand->add_option("--out", options->trajectoryPath,
                         "Write every moving body's state at every step as CSV");
  runCommand->add_option("--stats", options->statsPath, "Write a JSON summary of the run");
  runCommand->callback([options] { run(*options); });

  app.add_subcommand("scenes", "List the built-in scenes")->callback(listScenes);

  app.add_subcommand("demo", "Run the free-flight samples and print what they measure")
      ->callback([] {
        if (!samples::runFreeFlightDemo(std::cout))
          throw CommandError("a free-flight measurement is outside its expected bound");
      });
}

}  // namespace coulomb::cli
