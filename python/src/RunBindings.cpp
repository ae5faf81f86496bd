// coulomb.run, coulomb.run_batch and the conformance cases (docs/python.md "Running scenes"):
// a scene (built-in name, JSON or URDF file, or a dict in the JSON scene format) stepped in C++
// with the GIL released, its final state returned as NumPy arrays. run_batch steps independent
// worlds on C++ threads; each world is the same computation as alone, so the results are
// bit-identical whatever the thread count.
#include <coulomb/engine/CoulombError.hpp>
#include <coulomb/engine/World.hpp>
#include <coulomb/io/SceneLoader.hpp>

#include <pybind11/stl.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <memory>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "Bindings.hpp"
#include "NumpyConversion.hpp"
#include "PyWorld.hpp"
#include "SceneInput.hpp"
#include "conformance/ConformanceCase.hpp"
#include "scenes/SceneOverrides.hpp"

namespace py = pybind11;
using coulomb::engine::CoulombError;

namespace coulomb::python {
namespace {

struct RunResult {
  std::string scene;
  std::uint64_t steps = 0;
  double time = 0.0;      // [s] simulated
  double timeStep = 0.0;  // [s]
  std::uint64_t stateHash = 0;
  std::vector<std::string> bodies;  // live bodies in slot order (scene order, then link proxies)
  Eigen::MatrixXd positions, quaternions, linearVelocities, angularVelocities;
  double energyStart = 0.0, energyEnd = 0.0;  // [J] World::mechanicalEnergy
  std::uint64_t islandSolves = 0, iterations = 0, unconverged = 0, fallbacks = 0;
  double maxResidual = 0.0;  // common e_rel, max over islands and steps
  double maxJointGap = 0.0;  // [m] largest anchor gap after any step
  double seconds = 0.0;      // wall clock of the steps
};

// Steps `world` and reads its final state; no Python object is touched (runs without the GIL).
RunResult runWorld(engine::World& world, std::uint64_t steps, std::string name) {
  RunResult r;
  r.scene = std::move(name);
  r.timeStep = world.settings().timeStep;
  r.energyStart = world.mechanicalEnergy();
  const auto start = std::chrono::steady_clock::now();
  for (std::uint64_t i = 0; i < steps; ++i) {
    const engine::StepReport& report = world.step();
    for (const engine::IslandReport& island : report.islands) {
      ++r.islandSolves;
      r.iterations += static_cast<std::uint64_t>(island.solve.iterations);
      r.unconverged += island.converged() ? 0 : 1;
      r.maxResidual = std::max(r.maxResidual, island.solve.residual);
    }
    r.fallbacks += report.fallbacks();
    r.maxJointGap = std::max(r.maxJointGap, report.joints.maxLinearError);
  }
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  r.steps = world.stepCount();
  r.time = world.time();
  r.stateHash = world.stateHash();
  r.energyEnd = world.mechanicalEnergy();
  const geometry::BodyState& s = world.state();
  std::vector<std::size_t> live;
  for (std::size_t i = 0; i < s.size(); ++i)
    if (s.alive[i]) live.push_back(i);
  const auto n = static_cast<Eigen::Index>(live.size());
  r.positions.resize(n, 3);
  r.quaternions.resize(n, 4);
  r.linearVelocities.resize(n, 3);
  r.angularVelocities.resize(n, 3);
  for (Eigen::Index k = 0; k < n; ++k) {
    const std::size_t i = live[static_cast<std::size_t>(k)];
    r.bodies.push_back(world.name(world.idAt(i)));
    r.positions.row(k) = s.poses[i].position.transpose();
    const Eigen::Quaterniond& q = s.poses[i].rotation;
    r.quaternions.row(k) << q.w(), q.x(), q.y(), q.z();
    r.linearVelocities.row(k) = s.linearVelocities[i].transpose();
    r.angularVelocities.row(k) = s.angularVelocities[i].transpose();
  }
  return r;
}

RunResult runScene(const engine::io::Scene& scene) {
  engine::World world = engine::io::buildWorld(scene);
  return runWorld(world, scene.steps, scene.name);
}

RunResult run(const py::handle& scene, std::optional<std::uint64_t> steps, std::optional<double> dt,
              std::optional<std::string> solver, std::optional<double> tol,
              std::optional<int> maxIterations, std::optional<double> mu,
              std::optional<std::string> jointEnergy) {
  const engine::io::Scene loaded = sceneFrom(
      scene,
      overridesFrom(steps, dt, std::move(solver), tol, maxIterations, mu, std::move(jointEnergy)));
  py::gil_scoped_release released;
  return runScene(loaded);
}

// One entry of run_batch: a scene to build, or a World (coulomb.World) to step in place.
struct BatchItem {
  std::optional<engine::io::Scene> scene;
  std::shared_ptr<PyWorld> world;
};

std::vector<RunResult> runBatch(const py::iterable& items, int threads,
                                std::optional<std::uint64_t> steps, std::optional<double> dt,
                                std::optional<std::string> solver, std::optional<double> tol,
                                std::optional<int> maxIterations, std::optional<double> mu,
                                std::optional<std::string> jointEnergy) {
  if (threads < 0) throw py::value_error("threads: expected >= 0 (0 = every core)");
  if (py::isinstance<py::str>(items) || py::isinstance<py::dict>(items))
    throw py::value_error("scenes: expected a list of scenes or worlds, got one scene");
  const scenes::SceneOverrides overrides =
      overridesFrom(steps, dt, std::move(solver), tol, maxIterations, mu, std::move(jointEnergy));
  std::vector<BatchItem> batch;
  for (const py::handle& item : items) {
    if (py::isinstance<PyWorld>(item)) {
      if (!steps) throw py::value_error("steps: required when the batch holds worlds");
      auto world = item.cast<std::shared_ptr<PyWorld>>();
      for (const BatchItem& other : batch)
        if (other.world == world)
          throw py::value_error(
              "scenes: the same World twice (it would be stepped by two threads)");
      batch.push_back({std::nullopt, std::move(world)});
    } else {
      batch.push_back({sceneFrom(item, overrides), nullptr});
    }
  }
  std::vector<std::unique_ptr<SteppingGuard>> guards;  // the worlds are busy until the end
  for (const BatchItem& item : batch)
    if (item.world) guards.push_back(std::make_unique<SteppingGuard>(*item.world));
  std::vector<RunResult> results(batch.size());
  std::vector<std::exception_ptr> errors(batch.size());
  {
    py::gil_scoped_release released;
    const unsigned cores = std::max(1u, std::thread::hardware_concurrency());
    const std::size_t workers =
        std::min<std::size_t>(batch.size(), threads == 0 ? cores : static_cast<unsigned>(threads));
    std::atomic<std::size_t> next{0};
    auto work = [&] {
      for (std::size_t i = next++; i < batch.size(); i = next++) {
        try {
          results[i] = batch[i].world ? runWorld(batch[i].world->world, *steps, "world")
                                      : runScene(*batch[i].scene);
        } catch (...) {
          errors[i] = std::current_exception();
        }
      }
    };
    std::vector<std::thread> pool;
    for (std::size_t w = 1; w < workers; ++w) pool.emplace_back(work);
    work();  // the calling thread is a worker too
    for (std::thread& t : pool) t.join();
  }
  for (const std::exception_ptr& error : errors)  // the first failing item, in input order
    if (error) std::rethrow_exception(error);
  return results;
}

// The scalar fields of a RunResult by their Python names: one table for the properties, to_dict
// and pickling.
struct NumberField {
  const char* name;
  double RunResult::*member;
  const char* doc;
};
struct CountField {
  const char* name;
  std::uint64_t RunResult::*member;
  const char* doc;
};
constexpr NumberField kNumbers[] = {
    {"time", &RunResult::time, "[s] simulated time"},
    {"time_step", &RunResult::timeStep, "[s]"},
    {"energy_start", &RunResult::energyStart, "[J] mechanical energy before the first step"},
    {"energy_end", &RunResult::energyEnd, "[J] after the last step"},
    {"max_residual", &RunResult::maxResidual, "common e_rel, max over islands and steps"},
    {"max_joint_gap", &RunResult::maxJointGap, "[m] largest joint gap after any step"},
    {"seconds", &RunResult::seconds, "[s] wall clock of the steps"}};
constexpr CountField kCounts[] = {
    {"steps", &RunResult::steps, "steps taken"},
    {"state_hash", &RunResult::stateHash,
     "hash of every pose and velocity (bit patterns), as `coulomb run` prints it"},
    {"island_solves", &RunResult::islandSolves, "island solves over the run"},
    {"iterations", &RunResult::iterations, "solver iterations, summed"},
    {"unconverged", &RunResult::unconverged, "island solves left above the tolerance"},
    {"fallbacks", &RunResult::fallbacks, "fallback attempts over the run"}};

py::dict toDict(const RunResult& r) {
  py::dict d;
  d["scene"] = r.scene;
  d["bodies"] = r.bodies;
  for (const NumberField& f : kNumbers) d[f.name] = r.*f.member;
  for (const CountField& f : kCounts) d[f.name] = r.*f.member;
  d["positions"] = toNumpy(r.positions);
  d["quaternions"] = toNumpy(r.quaternions);
  d["linear_velocities"] = toNumpy(r.linearVelocities);
  d["angular_velocities"] = toNumpy(r.angularVelocities);
  return d;
}

RunResult fromDict(const py::dict& d) {
  RunResult r;
  r.scene = d["scene"].cast<std::string>();
  r.bodies = d["bodies"].cast<std::vector<std::string>>();
  for (const NumberField& f : kNumbers) r.*f.member = d[f.name].cast<double>();
  for (const CountField& f : kCounts) r.*f.member = d[f.name].cast<std::uint64_t>();
  const auto n = static_cast<Eigen::Index>(r.bodies.size());
  r.positions = toMatrix(d["positions"], "positions", n, 3);
  r.quaternions = toMatrix(d["quaternions"], "quaternions", n, 4);
  r.linearVelocities = toMatrix(d["linear_velocities"], "linear_velocities", n, 3);
  r.angularVelocities = toMatrix(d["angular_velocities"], "angular_velocities", n, 3);
  return r;
}

void bindRunResult(py::module_& m) {
  py::class_<RunResult> result(m, "RunResult", "The end of a scene run (docs/python.md)");
  for (const NumberField& f : kNumbers) result.def_readonly(f.name, f.member, f.doc);
  for (const CountField& f : kCounts) result.def_readonly(f.name, f.member, f.doc);
  result.def_readonly("scene", &RunResult::scene)
      .def_property_readonly("state_hash_hex",
                             [](const RunResult& r) { return hashText(r.stateHash); })
      .def_readonly("bodies", &RunResult::bodies, "names of the live bodies, in slot order")
      .def_property_readonly(
          "positions", [](const RunResult& r) { return toNumpy(r.positions); },
          "(N, 3) centre of mass positions [m]")
      .def_property_readonly(
          "quaternions", [](const RunResult& r) { return toNumpy(r.quaternions); },
          "(N, 4) orientations (w, x, y, z)")
      .def_property_readonly(
          "linear_velocities", [](const RunResult& r) { return toNumpy(r.linearVelocities); },
          "(N, 3) [m/s]")
      .def_property_readonly(
          "angular_velocities", [](const RunResult& r) { return toNumpy(r.angularVelocities); },
          "(N, 3) [rad/s], world frame")
      .def("to_dict", &toDict)
      .def("__repr__",
           [](const RunResult& r) {
             return "<coulomb.RunResult " + r.scene + ": " + std::to_string(r.steps) +
                    " steps, state hash " + hashText(r.stateHash) + ">";
           })
      .def(py::pickle([](const RunResult& r) { return toDict(r); },
                      [](const py::dict& d) { return fromDict(d); }));
}

void bindConformance(py::module_& m) {
  py::class_<conformance::CaseRun>(m, "ConformanceResult",
                                   "One conformance case with one solver (docs/conformance.md)")
      .def_readonly("passed", &conformance::CaseRun::passed)
      .def_readonly("metric", &conformance::CaseRun::metric)
      .def_readonly("detail", &conformance::CaseRun::detail)
      .def_readonly("steps", &conformance::CaseRun::steps)
      .def_readonly("ms_per_step", &conformance::CaseRun::msPerStep)
      .def_readonly("max_residual", &conformance::CaseRun::maxResidual)
      .def_readonly("mean_iterations", &conformance::CaseRun::meanIterations)
      .def_readonly("max_iterations", &conformance::CaseRun::maxIterations)
      .def_readonly("fallbacks", &conformance::CaseRun::fallbacks)
      .def_readonly("state_hash", &conformance::CaseRun::stateHash)
      .def_property_readonly("state_hash_hex",
                             [](const conformance::CaseRun& r) { return hashText(r.stateHash); })
      .def("__repr__", [](const conformance::CaseRun& r) {
        return std::string("<coulomb.ConformanceResult ") + (r.passed ? "pass" : "FAIL") + ": " +
               r.detail + ">";
      });
  m.def(
      "conformance_cases",
      [] {
        std::vector<py::dict> cases;
        for (const conformance::ConformanceCase& c : conformance::allCases()) {
          py::dict d;
          d["name"] = c.name;
          d["scene"] = c.scene;
          d["section"] = c.section;
          d["metric"] = c.metricName;
          d["criterion"] = c.criterion;
          cases.push_back(d);
        }
        return cases;
      },
      "The conformance cases (`coulomb conformance --list`): name, scene, section, metric, "
      "criterion");
  m.def(
      "run_conformance",
      [](const std::string& name, const std::string& solver, double scale) {
        const conformance::ConformanceCase& c = conformance::findCase(name);
        std::string error;
        if (!solvers::parseSolverChoice(solver, error)) throw CoulombError("solver: " + error);
        if (!(scale > 0.0)) throw py::value_error("scale: expected > 0");
        py::gil_scoped_release released;
        return c.run({solver, scale});
      },
      py::arg("case"), py::arg("solver") = "auto", py::arg("scale") = 1.0,
      "Runs one conformance case with one solver, as `coulomb conformance --cases CASE "
      "--solvers SOLVER` does: the verdict, the metric and the state hash are the CLI's.");
}

}  // namespace

void bindRun(py::module_& m) {
  bindRunResult(m);
  m.def("run", &run, py::arg("scene"), py::kw_only(), py::arg("steps") = py::none(),
        py::arg("dt") = py::none(), py::arg("solver") = py::none(), py::arg("tol") = py::none(),
        py::arg("max_iterations") = py::none(), py::arg("mu") = py::none(),
        py::arg("joint_energy") = py::none(),
        "Runs a scene (built-in name, JSON or .urdf file, or a dict in the JSON scene format) "
        "for `steps` steps (default: the scene's) and returns its final state. Overrides as "
        "`coulomb run`: dt, solver, tol, max_iterations, mu (every shape's friction), "
        "joint_energy (none, modified or exact: every joint's energy target).");
  m.def("run_batch", &runBatch, py::arg("scenes"), py::kw_only(), py::arg("threads") = 1,
        py::arg("steps") = py::none(), py::arg("dt") = py::none(), py::arg("solver") = py::none(),
        py::arg("tol") = py::none(), py::arg("max_iterations") = py::none(),
        py::arg("mu") = py::none(), py::arg("joint_energy") = py::none(),
        "Runs many scenes (names, files, dicts) or coulomb.World objects (stepped in place by "
        "`steps`) on `threads` C++ threads (0 = every core) with the GIL released; the results, "
        "in input order, are those of running them one by one.");
  bindConformance(m);
}

}  // namespace coulomb::python
