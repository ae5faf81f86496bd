// coulomb.scenes and coulomb.capture_problems (docs/python.md "Problems from a running world"):
// every island problem a scene's world assembles, as the solvers see it (before the solve,
// with the world's warm start), the way `coulomb run --capture` writes them, but in memory and
// with every row kind kept.
#include <coulomb/engine/World.hpp>
#include <coulomb/io/SceneLoader.hpp>
#include <coulomb/solvers/ContactProblem.hpp>

#include <pybind11/stl.h>

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "Bindings.hpp"
#include "CapturedProblem.hpp"
#include "SceneInput.hpp"
#include "scenes/SceneRegistry.hpp"

namespace py = pybind11;
using coulomb::solvers::ContactProblem;

namespace coulomb::python {
namespace {

// A copy that owns a block-sparse W (the world's operator refers to buffers it refills), named
// as `coulomb run --capture` names its files: <scene>_step<N>_island<K>.
ContactProblem detached(const ContactProblem& p, const std::string& scene, std::uint64_t step,
                        std::int32_t island) {
  ContactProblem copy = p;
  copy.name = scene + "_step" + std::to_string(step) + "_island" + std::to_string(island);
  copy.W = solvers::DelassusOperator::blockSparse(p.W.toBlockSparse(p.blockSizes()));
  return copy;
}

std::vector<CapturedProblem> capture(const py::handle& scene, std::optional<std::uint64_t> steps,
                                     std::optional<std::uint64_t> atStep) {
  const engine::io::Scene loaded = sceneFrom(scene, {});
  const std::uint64_t count = steps ? *steps : atStep ? *atStep + 1 : loaded.steps;
  py::gil_scoped_release released;
  engine::World world = engine::io::buildWorld(loaded);
  return stepCapturing(world, count, atStep, loaded.name);
}

}  // namespace

std::vector<CapturedProblem> stepCapturing(engine::World& world, std::uint64_t steps,
                                           std::optional<std::uint64_t> onlyStep,
                                           const std::string& name) {
  std::vector<CapturedProblem> captured;
  world.setProblemObserver([&](std::int32_t island, const ContactProblem& problem) {
    const std::uint64_t step = world.stepCount();
    if (!onlyStep || *onlyStep == step)
      captured.push_back({step, island, detached(problem, name, step, island)});
  });
  try {
    for (std::uint64_t i = 0; i < steps; ++i) world.step();
  } catch (...) {
    world.setProblemObserver({});
    throw;
  }
  world.setProblemObserver({});
  return captured;
}

void bindCapture(py::module_& m) {
  py::class_<CapturedProblem>(m, "CapturedProblem", "An island's problem at one step of a scene")
      .def_readonly("step", &CapturedProblem::step, "index of the step (0 = the first)")
      .def_readonly("island", &CapturedProblem::island, "the island's id in that step's report")
      .def_readonly("problem", &CapturedProblem::problem)
      .def("__repr__", [](const CapturedProblem& c) {
        return "<coulomb.CapturedProblem step " + std::to_string(c.step) + ", island " +
               std::to_string(c.island) + ": " + std::to_string(c.problem.size()) + " unknowns>";
      });

  m.def(
      "scenes",
      [] {
        std::vector<std::string> names;
        for (const scenes::BuiltinScene& s : scenes::builtinScenes()) names.emplace_back(s.name);
        return names;
      },
      "The names of the built-in scenes (`coulomb scenes`)");
  m.def("capture_problems", &capture, py::arg("scene"), py::kw_only(),
        py::arg("steps") = py::none(), py::arg("at_step") = py::none(),
        "Runs a scene (a built-in name, a JSON or URDF file, or a dict) for `steps` steps "
        "(default: at_step + 1, "
        "else the scene's own count) and returns the problem of every island of every step, or "
        "of step `at_step` only, as the solver received it (warm start included).");
}

}  // namespace coulomb::python
