// Contact and sensor events, kinematic targets and colliders on live bodies of coulomb.World
// (docs/python.md "Contact events, sensors, kinematic bodies, colliders on live bodies";
// engine/ContactEvents.hpp): the events of the last step as lists of dicts naming bodies and
// colliders by integer handles.
#include <pybind11/stl.h>

#include <cstdint>
#include <optional>

#include "Bindings.hpp"
#include "NumpyConversion.hpp"
#include "PyWorld.hpp"
#include "SceneInput.hpp"

namespace py = pybind11;

namespace coulomb::python {
namespace {

const char* typeName(engine::ContactEventType type) {
  switch (type) {
    case engine::ContactEventType::Begin:
      return "begin";
    case engine::ContactEventType::Persist:
      return "persist";
    default:
      return "end";
  }
}

py::dict contactEventDict(const engine::ContactEvent& e) {
  py::dict d;
  d["type"] = typeName(e.type);
  d["body_a"] = handleOf(e.bodyA);
  d["body_b"] = handleOf(e.bodyB);
  d["collider_a"] = handleOf(e.colliderA);
  d["collider_b"] = handleOf(e.colliderB);
  d["normal"] = toNumpy(Eigen::VectorXd(e.normal));
  Eigen::MatrixXd points(e.pointCount, 3);
  for (int k = 0; k < e.pointCount; ++k)
    points.row(k) = e.points[static_cast<std::size_t>(k)].position.transpose();
  d["points"] = toNumpy(points);
  d["normal_impulse"] = e.normalImpulse;
  d["tangent_impulse"] = toNumpy(Eigen::VectorXd(e.tangentImpulse));
  d["approach_speed"] = e.approachSpeed;
  return d;
}

py::dict sensorEventDict(const engine::SensorEvent& e) {
  py::dict d;
  d["begin"] = e.begin;
  d["sensor_body"] = handleOf(e.sensorBody);
  d["visitor_body"] = handleOf(e.visitorBody);
  d["sensor_collider"] = handleOf(e.sensor);
  d["visitor_collider"] = handleOf(e.visitor);
  return d;
}

}  // namespace

void bindEvents(py::module_& m) {
  py::reinterpret_borrow<py::class_<PyWorld, std::shared_ptr<PyWorld>>>(m.attr("World"))
      .def(
          "contact_events",
          [](const PyWorld& w) {
            py::list out;
            for (const engine::ContactEvent& e : use(w).contactEvents())
              out.append(contactEventDict(e));
            return out;
          },
          "the contact pairs that began, persisted or ended in the last step, in collider-pair "
          "order: dicts (type 'begin'/'persist'/'end', body_a, body_b, collider_a, collider_b, "
          "normal from a to b, points (n, 3), normal_impulse [N s], tangent_impulse (3) [N s], "
          "approach_speed [m/s])")
      .def(
          "sensor_events",
          [](const PyWorld& w) {
            py::list out;
            for (const engine::SensorEvent& e : use(w).sensorEvents())
              out.append(sensorEventDict(e));
            return out;
          },
          "overlaps with sensor shapes ('sensor': true) that began or ended in the last step: "
          "dicts (begin, sensor_body, visitor_body, sensor_collider, visitor_collider)")
      .def(
          "set_kinematic_target",
          [](PyWorld& w, std::int64_t body, const py::object& position, const py::object& rotation,
             std::optional<double> dt) {
            engine::World& world = use(w);
            const geometry::BodyId id = idOf<geometry::BodyId>(w, body, "body");
            world.setKinematicTarget(id, poseFrom(position, rotation),
                                     dt.value_or(world.settings().timeStep));
          },
          py::arg("body"), py::arg("position"), py::kw_only(), py::arg("rotation") = py::none(),
          py::arg("dt") = py::none(),
          "moves a kinematic body so that the next step of dt (default: the world's time step) "
          "ends at this pose of its reference frame (rotation: quaternion w, x, y, z)")
      .def(
          "add_collider",
          [](PyWorld& w, std::int64_t body, const py::dict& shape) {
            const geometry::BodyId id = idOf<geometry::BodyId>(w, body, "body");
            return handleOf(use(w).addCollider(id, shapeDescFrom(shape, "add_collider")));
          },
          py::arg("body"), py::arg("shape"),
          "adds a shape (JSON scene format, placed in the body's reference frame) to a live body; "
          "its mass stays as it is; returns the collider's handle")
      .def(
          "remove_collider",
          [](PyWorld& w, std::int64_t collider) {
            const auto bits = static_cast<std::uint64_t>(collider);
            use(w).removeCollider({static_cast<std::uint32_t>(bits & 0xffffffffu),
                                   static_cast<std::uint32_t>(bits >> 32)});
          },
          py::arg("collider"), "removes a collider (from add_collider, events or query hits)");
}

}  // namespace coulomb::python
