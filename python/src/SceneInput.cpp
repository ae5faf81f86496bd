#include "SceneInput.hpp"

#include <cstdio>
#include <utility>

namespace py = pybind11;

namespace coulomb::python {

std::string jsonText(const py::handle& object) {
  // NaN and infinities are not JSON: refused here with Python's own ValueError ("Out of range
  // float values are not JSON compliant") rather than as a parse error of the text.
  return py::module_::import("json")
      .attr("dumps")(object, py::arg("allow_nan") = false)
      .cast<std::string>();
}

std::string hashText(std::uint64_t hash) {
  char text[32];
  std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(hash));
  return text;
}

scenes::SceneOverrides overridesFrom(std::optional<std::uint64_t> steps, std::optional<double> dt,
                                     std::optional<std::string> solver, std::optional<double> tol,
                                     std::optional<int> maxIterations, std::optional<double> mu,
                                     std::optional<std::string> jointEnergy) {
  scenes::SceneOverrides o;
  o.steps = steps;
  o.timeStep = dt;
  o.solver = std::move(solver);
  o.tolerance = tol;
  o.maxIterations = maxIterations;
  o.friction = mu;
  o.jointEnergy = std::move(jointEnergy);
  return o;
}

engine::io::Scene sceneFrom(const py::handle& scene, const scenes::SceneOverrides& overrides) {
  if (py::isinstance<py::dict>(scene)) {
    const std::string text = jsonText(scene);
    const py::object name = scene.cast<py::dict>().attr("get")("name", "unnamed");
    engine::io::Scene parsed =
        engine::io::parseScene(text, "<scene dict '" + py::str(name).cast<std::string>() + "'>");
    scenes::applyOverrides(parsed, overrides);
    return parsed;
  }
  if (!py::isinstance<py::str>(scene) && !py::hasattr(scene, "__fspath__"))
    throw py::value_error("scene: expected a built-in name, a file path or a dict, got " +
                          py::str(py::type::of(scene)).cast<std::string>());
  return scenes::resolveScene(py::str(scene).cast<std::string>(), overrides);
}

engine::ShapeDesc shapeDescFrom(const py::dict& shape, const std::string& what) {
  py::dict body;
  body["name"] = what;
  body["type"] = "static";
  py::list shapes;
  shapes.append(shape);
  body["shapes"] = shapes;
  py::list bodies;
  bodies.append(body);
  py::dict scene;
  scene["name"] = what;
  scene["bodies"] = bodies;
  return engine::io::parseScene(jsonText(scene), what).bodies.at(0).shapes.at(0);
}

}  // namespace coulomb::python
