// coulomb.World and coulomb.Robot (docs/python.md "A world from Python"): a live world built
// from a scene or empty, stepped from Python, with its state as NumPy arrays (one copy per call,
// no Python loop per body), bodies added from the JSON scene format, contacts as a structured
// array, snapshots as bytes, and URDF robots with their joint state. Bodies are named by integer
// handles (slot and generation: a removed body's handle is stale and raises coulomb.Error).
#include <coulomb/engine/ArticulationStage.hpp>
#include <coulomb/engine/CoulombError.hpp>
#include <coulomb/engine/World.hpp>
#include <coulomb/io/SceneLoader.hpp>
#include <coulomb/io/Snapshot.hpp>
#include <coulomb/io/UrdfScene.hpp>

#include <pybind11/stl.h>

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "Bindings.hpp"
#include "CapturedProblem.hpp"
#include "NumpyConversion.hpp"
#include "PyWorld.hpp"
#include "SceneInput.hpp"

namespace py = pybind11;
using coulomb::engine::CoulombError;
using coulomb::geometry::ArticulationId;
using coulomb::geometry::BodyId;

namespace coulomb::python {
namespace {

BodyId bodyOf(const PyWorld& w, std::int64_t handle) {
  return idOf<BodyId>(w, handle, "body");
}

geometry::JointId jointOf(const PyWorld& w, std::int64_t handle) {
  return idOf<geometry::JointId>(w, handle, "joint");
}

// A joint in the JSON scene format whose ends name live bodies (docs/scene-format.md "Joints").
std::int64_t addJoint(PyWorld& w, const py::dict& desc) {
  const std::string text = jsonText(desc);
  return handleOf(use(w).createJoint(engine::io::parseLiveJoint(text, use(w), "add_joint")));
}

std::vector<std::size_t> liveSlots(const engine::World& world) {
  std::vector<std::size_t> live;
  const geometry::BodyState& s = world.state();
  for (std::size_t i = 0; i < s.size(); ++i)
    if (s.alive[i]) live.push_back(i);
  return live;
}

// One (N, width) array over the live bodies, filled row by row by `fill(slot, row pointer)`.
template <class Fill>
py::array_t<double> perBody(const engine::World& world, py::ssize_t width, Fill fill) {
  const std::vector<std::size_t> live = liveSlots(world);
  py::array_t<double> out({static_cast<py::ssize_t>(live.size()), width});
  double* data = out.mutable_data();
  for (std::size_t k = 0; k < live.size(); ++k) fill(live[k], data + k * width);
  return out;
}

void put3(double* row, const Eigen::Vector3d& v) {
  row[0] = v.x();
  row[1] = v.y();
  row[2] = v.z();
}

Eigen::Vector3d vector3(const py::handle& v, const char* name) {
  return toVector(v, name, 3);
}

std::shared_ptr<PyWorld> makeWorld(const py::object& scene, std::optional<double> dt,
                                   std::optional<std::string> solver, std::optional<double> tol,
                                   std::optional<int> maxIterations, std::optional<double> mu,
                                   std::optional<std::string> jointEnergy,
                                   const py::object& gravity, const py::object& threads) {
  const scenes::SceneOverrides overrides = overridesFrom(std::nullopt, dt, std::move(solver), tol,
                                                         maxIterations, mu, std::move(jointEnergy));
  engine::io::Scene loaded;
  if (!scene.is_none()) {
    loaded = sceneFrom(scene, overrides);
  } else {
    loaded.name = "world";
    scenes::applyOverrides(loaded, overrides);
  }
  if (!gravity.is_none()) loaded.settings.gravity = vector3(gravity, "gravity");
  if (!threads.is_none())  // a count or "hardware" (docs/python.md)
    loaded.settings.threads = scenes::parseThreads(py::isinstance<py::str>(threads)
                                                       ? threads.cast<std::string>()
                                                       : std::to_string(threads.cast<long long>()),
                                                   "threads");
  return std::make_shared<PyWorld>(engine::io::buildWorld(loaded));
}

// A body from the JSON scene format (docs/scene-format.md "bodies"), with named materials.
std::int64_t addBody(PyWorld& w, const py::dict& desc, const py::object& materials) {
  py::dict scene;
  scene["name"] = "add_body";
  py::list bodies;
  bodies.append(desc);
  scene["bodies"] = bodies;
  if (!materials.is_none()) scene["materials"] = materials;
  const std::string text = jsonText(scene);
  const engine::io::Scene parsed = engine::io::parseScene(text, "add_body");
  return handleOf(use(w).createBody(parsed.bodies.at(0)));
}

py::dict reportDict(const engine::StepReport& r) {
  py::dict d;
  d["step"] = r.stepIndex;
  d["time"] = r.time;
  d["time_step"] = r.timeStep;
  d["dynamic_bodies"] = r.dynamicBodies;
  d["sleeping_bodies"] = r.sleepingBodies;
  d["contact_points"] = r.collision.contactPoints;
  d["touching_pairs"] = r.collision.touchingPairs;
  py::list islands;
  for (const engine::IslandReport& i : r.islands) {
    py::dict island;
    island["island"] = i.island;
    island["bodies"] = i.bodies;
    island["contacts"] = i.contacts;
    island["unknowns"] = i.unknowns;
    island["solver"] = i.solve.solver;
    island["status"] = solvers::statusName(i.status);
    island["iterations"] = i.solve.iterations;
    island["residual"] = i.solve.residual;
    std::vector<std::string> attempts;
    for (const solvers::SolverReport& a : i.attempts) attempts.push_back(a.solver);
    island["attempts"] = attempts;
    island["reason"] = i.reason();
    islands.append(island);
  }
  d["islands"] = islands;
  d["max_joint_gap"] = r.joints.maxLinearError;
  d["correction_iterations"] = r.joints.correctionIterations;
  d["energy_projections"] = r.joints.energyProjections;
  d["warnings"] = r.warnings;
  d["seconds"] = r.seconds;
  return d;
}

// The points of the last step's manifolds as one structured array.
py::object contactArray(const PyWorld& w) {
  const auto& manifolds = use(w).contacts();
  std::size_t count = 0;
  for (const geometry::ContactManifold& m : manifolds) count += m.activePoints().size();
  py::module_ np = py::module_::import("numpy");
  py::list fields;
  fields.append(py::make_tuple("body_a", "i8"));
  fields.append(py::make_tuple("body_b", "i8"));
  fields.append(py::make_tuple("point", "f8", 3));
  fields.append(py::make_tuple("normal", "f8", 3));
  fields.append(py::make_tuple("depth", "f8"));
  fields.append(py::make_tuple("friction", "f8"));
  fields.append(py::make_tuple("normal_impulse", "f8"));
  fields.append(py::make_tuple("tangent_impulse", "f8", 2));
  py::object out = np.attr("zeros")(count, py::arg("dtype") = fields);
  std::vector<std::int64_t> a, b;
  Eigen::MatrixXd point(count, 3), normal(count, 3), tangent(count, 2);
  Eigen::VectorXd depth(count), friction(count), impulse(count);
  Eigen::Index k = 0;
  for (const geometry::ContactManifold& m : manifolds)
    for (const geometry::ContactPoint& p : m.activePoints()) {
      a.push_back(handleOf(m.bodyA));
      b.push_back(handleOf(m.bodyB));
      point.row(k) = p.position.transpose();
      normal.row(k) = m.normal.transpose();
      depth[k] = p.depth;
      friction[k] = m.friction;
      impulse[k] = p.normalImpulse;
      tangent.row(k) = p.tangentImpulse.transpose();
      ++k;
    }
  out.attr("__setitem__")("body_a", py::array(py::cast(a)));
  out.attr("__setitem__")("body_b", py::array(py::cast(b)));
  out.attr("__setitem__")("point", toNumpy(point));
  out.attr("__setitem__")("normal", toNumpy(normal));
  out.attr("__setitem__")("depth", toNumpy(depth));
  out.attr("__setitem__")("friction", toNumpy(friction));
  out.attr("__setitem__")("normal_impulse", toNumpy(impulse));
  out.attr("__setitem__")("tangent_impulse", toNumpy(tangent));
  return out;
}

// A robot of the world: its joints by name, its state, forces and motor targets.
struct Robot {
  std::shared_ptr<PyWorld> world;
  ArticulationId id;

  [[nodiscard]] const joints::tree::Articulation& model() const {
    return use(*world).articulations().model(id);
  }
  // The link whose joint is called `joint`; CoulombError listing the names otherwise.
  [[nodiscard]] int linkOfJoint(const std::string& joint) const {
    const joints::tree::Articulation& m = model();
    for (int i = 0; i < m.linkCount(); ++i)
      if (m.link(i).joint.name == joint) return i;
    std::string known;
    for (const std::string& n : jointNames()) known += " " + n;
    throw CoulombError("robot has no joint '" + joint + "'; its moving joints:" + known);
  }
  [[nodiscard]] std::vector<std::string> jointNames() const {  // joints with coordinates
    std::vector<std::string> names;
    const joints::tree::Articulation& m = model();
    for (int i = 0; i < m.linkCount(); ++i)
      if (m.link(i).joint.type != joints::tree::TreeJointType::Fixed)
        names.push_back(m.link(i).joint.name);
    return names;
  }
  void setMotorTarget(const std::string& joint, double target) const {
    const int link = linkOfJoint(joint);
    const auto& motors = use(*world).articulations().motors(id);
    for (std::size_t k = 0; k < motors.size(); ++k)
      if (motors[k].link == link) {
        use(*world).setJointMotorTarget(id, static_cast<int>(k), target);
        return;
      }
    throw CoulombError("joint '" + joint + "' has no motor");
  }
};

std::vector<Robot> robotsOf(const std::shared_ptr<PyWorld>& w) {
  std::vector<Robot> robots;
  const engine::ArticulationStage& stage = use(*w).articulations();
  for (std::size_t slot = 0; slot < stage.slots(); ++slot)
    if (const ArticulationId id = stage.idAt(slot); id.valid()) robots.push_back({w, id});
  return robots;
}

Robot loadUrdf(const std::shared_ptr<PyWorld>& w, const std::string& path, bool floating,
               const py::object& position, const std::string& name,
               const std::vector<std::string>& packagePaths, bool hold,
               const std::optional<double> onFloor) {
  engine::io::UrdfPlacement placement;
  placement.file = engine::io::resolveRobotFile(path, ".", "load_urdf");
  placement.name = name.empty() ? placement.file.stem().string() : name;
  placement.options.base = floating ? engine::io::UrdfBase::Floating : engine::io::UrdfBase::Fixed;
  if (!position.is_none()) placement.options.basePose.position = vector3(position, "position");
  for (const std::string& p : packagePaths) placement.options.packagePath.emplace_back(p);
  placement.options.gravity = use(*w).settings().gravity;
  placement.holdAllJoints = hold;
  placement.clearance = onFloor;
  const engine::ArticulationDesc desc = engine::io::placeUrdf(placement, path);
  return {w, use(*w).createArticulation(desc)};
}

void bindRobot(py::module_& m) {
  py::class_<Robot>(m, "Robot", "A URDF robot (a reduced-coordinate tree) of a World")
      .def_property_readonly("joint_names", &Robot::jointNames,
                             "the joints with coordinates, in tree order")
      .def_property_readonly("link_names",
                             [](const Robot& r) {
                               std::vector<std::string> names;
                               for (const auto& l : r.model().links()) names.push_back(l.name);
                               return names;
                             })
      .def_property_readonly("nq", [](const Robot& r) { return r.model().nq(); })
      .def_property_readonly("nv", [](const Robot& r) { return r.model().nv(); })
      .def_property_readonly(
          "q", [](const Robot& r) { return toNumpy(use(*r.world).articulations().q(r.id)); },
          "joint positions (nq; a floating base first: position, quaternion w x y z)")
      .def_property_readonly(
          "qd", [](const Robot& r) { return toNumpy(use(*r.world).articulations().qd(r.id)); },
          "joint velocities (nv)")
      .def(
          "set_state",
          [](const Robot& r, const py::object& q, const py::object& qd) {
            use(*r.world).setArticulationState(r.id, toVector(q, "q", r.model().nq()),
                                               toVector(qd, "qd", r.model().nv()));
          },
          py::arg("q"), py::arg("qd"))
      .def(
          "joint_q_index",
          [](const Robot& r, const std::string& joint) {
            return r.model().qIndex(r.linkOfJoint(joint));
          },
          py::arg("joint"), "index of the joint's first coordinate in q")
      .def(
          "joint_v_index",
          [](const Robot& r, const std::string& joint) {
            return r.model().vIndex(r.linkOfJoint(joint));
          },
          py::arg("joint"), "index of the joint's first velocity in qd and in joint forces")
      .def(
          "apply_joint_forces",
          [](const Robot& r, const py::object& tau) {
            use(*r.world).applyJointForces(r.id, toVector(tau, "tau", r.model().nv()));
          },
          py::arg("tau"), "generalised forces (nv) for the next step only")
      .def("set_motor_target", &Robot::setMotorTarget, py::arg("joint"), py::arg("target"),
           "new target of the joint's motor (position [rad or m] or velocity)")
      .def_property_readonly(
          "link_positions",
          [](const Robot& r) {
            const int n = r.model().linkCount();
            Eigen::MatrixXd p(n, 3);
            for (int i = 0; i < n; ++i)
              p.row(i) = use(*r.world).articulations().linkPose(r.id, i).position.transpose();
            return toNumpy(p);
          },
          "(links, 3) link frame origins [m]");
}

void bindWorldClass(py::module_& m) {
  py::class_<PyWorld, std::shared_ptr<PyWorld>>(
      m, "World", "A live world: from a scene (name, file or dict) or empty (docs/python.md)")
      .def(py::init(&makeWorld), py::arg("scene") = py::none(), py::kw_only(),
           py::arg("dt") = py::none(), py::arg("solver") = py::none(), py::arg("tol") = py::none(),
           py::arg("max_iterations") = py::none(), py::arg("mu") = py::none(),
           py::arg("joint_energy") = py::none(), py::arg("gravity") = py::none(),
           py::arg("threads") = py::none())
      .def(
          "step",
          [](PyWorld& w, int n) {
            if (n < 0) throw py::value_error("n: expected >= 0");
            const SteppingGuard guard(w);
            py::gil_scoped_release released;
            for (int i = 0; i < n; ++i) w.world.step();
          },
          py::arg("n") = 1, "advances n steps of the world's time step (GIL released)")
      .def(
          "step_capturing",
          [](PyWorld& w, std::uint64_t n) {
            const SteppingGuard guard(w);
            py::gil_scoped_release released;
            return stepCapturing(w.world, n, std::nullopt, "world");
          },
          py::arg("n") = 1,
          "steps like step(n) and returns every island's problem of those steps as its solver "
          "received it (coulomb.CapturedProblem, named world_step<N>_island<K>)")
      .def(
          "report", [](const PyWorld& w) { return reportDict(use(w).lastReport()); },
          "the last step's report as a dict (islands with solver, status, iterations, residual)")
      .def_property_readonly("time", [](const PyWorld& w) { return use(w).time(); })
      .def_property_readonly("step_count", [](const PyWorld& w) { return use(w).stepCount(); })
      .def_property_readonly(
          "threads", [](const PyWorld& w) { return use(w).threads(); },
          "the threads each step runs on (1 without oneTBB)")
      .def_property_readonly("time_step",
                             [](const PyWorld& w) { return use(w).settings().timeStep; })
      .def_property_readonly("state_hash", [](const PyWorld& w) { return use(w).stateHash(); })
      .def_property_readonly("state_hash_hex",
                             [](const PyWorld& w) { return hashText(use(w).stateHash()); })
      .def_property_readonly("mechanical_energy",
                             [](const PyWorld& w) { return use(w).mechanicalEnergy(); })
      .def_property_readonly("body_count", [](const PyWorld& w) { return use(w).bodyCount(); })
      .def_property_readonly(
          "bodies",
          [](const PyWorld& w) {
            std::vector<std::int64_t> handles;
            for (std::size_t slot : liveSlots(use(w)))
              handles.push_back(handleOf(use(w).idAt(slot)));
            return handles;
          },
          "handles of the live bodies, in the order of the state arrays")
      .def_property_readonly("body_names",
                             [](const PyWorld& w) {
                               std::vector<std::string> names;
                               for (std::size_t slot : liveSlots(use(w)))
                                 names.push_back(use(w).name(use(w).idAt(slot)));
                               return names;
                             })
      .def(
          "find_body",
          [](const PyWorld& w, const std::string& name) -> std::optional<std::int64_t> {
            const BodyId id = use(w).findBody(name);
            if (!id.valid()) return std::nullopt;
            return handleOf(id);
          },
          py::arg("name"), "the handle of the first body so named, or None")
      .def("add_body", &addBody, py::arg("desc"), py::arg("materials") = py::none(),
           "adds a body given as in the JSON scene format (docs/scene-format.md); returns its "
           "handle")
      .def(
          "remove_body", [](PyWorld& w, std::int64_t h) { use(w).removeBody(bodyOf(w, h)); },
          py::arg("body"))
      .def("positions",
           [](const PyWorld& w) {
             const geometry::BodyState& s = use(w).state();
             return perBody(use(w), 3,
                            [&](std::size_t i, double* row) { put3(row, s.poses[i].position); });
           })
      .def(
          "quaternions",
          [](const PyWorld& w) {
            const geometry::BodyState& s = use(w).state();
            return perBody(use(w), 4, [&](std::size_t i, double* row) {
              const Eigen::Quaterniond& q = s.poses[i].rotation;
              row[0] = q.w(), row[1] = q.x(), row[2] = q.y(), row[3] = q.z();
            });
          },
          "(N, 4) as (w, x, y, z)")
      .def("linear_velocities",
           [](const PyWorld& w) {
             const geometry::BodyState& s = use(w).state();
             return perBody(use(w), 3,
                            [&](std::size_t i, double* row) { put3(row, s.linearVelocities[i]); });
           })
      .def("angular_velocities",
           [](const PyWorld& w) {
             const geometry::BodyState& s = use(w).state();
             return perBody(use(w), 3,
                            [&](std::size_t i, double* row) { put3(row, s.angularVelocities[i]); });
           })
      .def(
          "set_velocity",
          [](PyWorld& w, std::int64_t h, const py::object& linear, const py::object& angular) {
            use(w).setVelocity(bodyOf(w, h), vector3(linear, "linear"),
                               vector3(angular, "angular"));
          },
          py::arg("body"), py::arg("linear"), py::arg("angular"))
      .def(
          "apply_force",
          [](PyWorld& w, std::int64_t h, const py::object& force, const py::object& point) {
            if (point.is_none())
              use(w).applyForce(bodyOf(w, h), vector3(force, "force"));
            else
              use(w).applyForceAtPoint(bodyOf(w, h), vector3(force, "force"),
                                       vector3(point, "point"));
          },
          py::arg("body"), py::arg("force"), py::arg("point") = py::none(),
          "a force [N] at the centre of mass or at a world point, for the next step")
      .def(
          "apply_torque",
          [](PyWorld& w, std::int64_t h, const py::object& torque) {
            use(w).applyTorque(bodyOf(w, h), vector3(torque, "torque"));
          },
          py::arg("body"), py::arg("torque"))
      .def("add_joint", &addJoint, py::arg("desc"),
           "adds a joint given as in the JSON scene format (docs/scene-format.md \"Joints\"), its "
           "ends named by body name; returns its handle")
      .def(
          "remove_joint", [](PyWorld& w, std::int64_t h) { use(w).removeJoint(jointOf(w, h)); },
          py::arg("joint"))
      .def_property_readonly("joint_count", [](const PyWorld& w) { return use(w).jointCount(); })
      .def(
          "joint_reaction",
          [](const PyWorld& w, std::int64_t h) {
            const engine::JointReaction& r = use(w).jointReaction(jointOf(w, h));
            return py::make_tuple(toNumpy(Eigen::VectorXd(r.force)),
                                  toNumpy(Eigen::VectorXd(r.torque)));
          },
          py::arg("joint"),
          "(force [N], torque [N m]) the joint applied to its body B, averaged over the last step")
      .def(
          "joint_broken",
          [](const PyWorld& w, std::int64_t h) { return use(w).jointBroken(jointOf(w, h)); },
          py::arg("joint"))
      .def("contacts", &contactArray,
           "the contact points of the last step: a structured array (body_a, body_b, point, "
           "normal (from a to b), depth, friction, normal_impulse, tangent_impulse)")
      .def(
          "save",
          [](const PyWorld& w) {
            const std::vector<std::uint8_t> bytes = engine::io::saveSnapshot(use(w));
            return py::bytes(reinterpret_cast<const char*>(bytes.data()), bytes.size());
          },
          "the state as bytes (a snapshot, docs/reliability.md)")
      .def(
          "restore",
          [](PyWorld& w, const py::bytes& data) {
            const std::string text = data;
            const auto* begin = reinterpret_cast<const std::uint8_t*>(text.data());
            engine::io::restoreSnapshot(use(w), {begin, text.size()}, "<bytes>");
          },
          py::arg("snapshot"), "back to a state saved by save() from a world of the same scene")
      .def("robots", &robotsOf, "the URDF robots (articulations) of the world")
      .def("load_urdf", &loadUrdf, py::arg("path"), py::kw_only(), py::arg("floating") = false,
           py::arg("position") = py::none(), py::arg("name") = "",
           py::arg("package_paths") = std::vector<std::string>{}, py::arg("hold") = false,
           py::arg("on_floor") = py::none(),
           "adds a URDF robot (reduced coordinates); hold: position motors keep every joint at "
           "its initial position; on_floor: lift it so its lowest shape rests that high above "
           "z = 0 [m]");
}

}  // namespace

void bindWorld(py::module_& m) {
  bindRobot(m);
  bindWorldClass(m);
}

}  // namespace coulomb::python
