// URDF robots in scenes: the JSON `urdf` section and one-file URDF scenes (UrdfScene.hpp).
#include <coulomb/io/JsonReader.hpp>
#include <coulomb/io/UrdfScene.hpp>
#include <coulomb/joints/tree/TreeKinematics.hpp>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <iterator>
#include <limits>
#include <sstream>
#include <variant>

namespace coulomb::engine::io {
namespace {

using geometry::Pose;

/// Lowest world z of a shape placed at `pose` (its support point along -z).
double lowestZ(const geometry::Shape& shape, const Pose& pose) {
  const Eigen::Matrix3d R = pose.rotation.toRotationMatrix();
  const double z = pose.position.z();
  const Eigen::Vector3d up = R.row(2).transpose();  // world z in the shape frame
  if (const auto* s = std::get_if<geometry::Sphere>(&shape)) return z - s->radius;
  if (const auto* b = std::get_if<geometry::Box>(&shape))
    return z - up.cwiseAbs().dot(b->halfExtents);
  if (const auto* c = std::get_if<geometry::Capsule>(&shape))
    return z - std::abs(up.z()) * c->halfLength - c->radius;
  if (const auto* c = std::get_if<geometry::Cylinder>(&shape))
    return z - std::abs(up.z()) * c->halfLength -
           c->radius * std::sqrt(std::max(0.0, 1.0 - up.z() * up.z()));
  const std::vector<Eigen::Vector3d>* vertices = nullptr;
  if (const auto* h = std::get_if<geometry::ConvexHull>(&shape)) vertices = &h->vertices;
  if (const auto* m = std::get_if<geometry::TriangleMesh>(&shape)) vertices = &m->vertices;
  double lowest = std::numeric_limits<double>::infinity();
  if (vertices != nullptr)
    for (const Eigen::Vector3d& v : *vertices) lowest = std::min(lowest, pose.apply(v).z());
  return lowest;  // a plane: +inf (ignored)
}

/// Lowest collision point of the articulation at its initial q, +inf without shapes.
double lowestPoint(const ArticulationDesc& desc, const UrdfModel& model) {
  const joints::tree::Articulation tree = toArticulation(model);
  const Eigen::VectorXd q = desc.q.value_or(tree.neutralConfiguration());
  const joints::tree::TreeKinematics kin = joints::tree::forwardKinematics(tree, q);
  double lowest = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < desc.links.size(); ++i)
    for (const ShapeDesc& s : desc.links[i].shapes)
      lowest = std::min(lowest, lowestZ(s.shape, kin.worldPoses[i] * s.localPose));
  return lowest;
}

std::vector<std::string> dofJointNames(const UrdfModel& model) {
  std::vector<std::string> names;
  for (const UrdfBody& body : model.bodies)
    if (body.joint.nv() == 1) names.push_back(body.joint.name);
  return names;
}

int linkOfJoint(const UrdfModel& model, const std::string& joint, const std::string& where) {
  for (std::size_t i = 0; i < model.bodies.size(); ++i)
    if (model.bodies[i].joint.name == joint && model.bodies[i].joint.nv() == 1)
      return static_cast<int>(i);
  std::string message = where + ": '" + model.file + "' has no moving 1-DOF joint '" + joint + "'";
  if (auto s = nearestName(joint, dofJointNames(model))) message += "; did you mean '" + *s + "'?";
  throw CoulombError(message);
}

std::map<std::string, double> parseJointValues(const JsonNode& node) {
  std::map<std::string, double> values;
  for (const std::string& joint : node.objectKeys())
    values[joint] = node.child(joint.c_str()).number();
  return values;
}

UrdfMotorSpec parseMotor(const JsonNode& node) {
  UrdfMotorSpec motor;
  if (node.raw().is_number()) {  // "joint": target position
    motor.target = node.number();
    return motor;
  }
  node.allowOnly({"mode", "target", "max_effort", "gain"});
  const std::string mode = node.string("mode", "position");
  if (mode == "velocity")
    motor.mode = JointMotorMode::Velocity;
  else if (mode != "position")
    node.child("mode").fail("expected \"position\" or \"velocity\" (got \"" + mode + "\")");
  motor.target = node.number("target", 0.0);
  if (node.has("max_effort")) motor.maxEffort = node.child("max_effort").positiveNumber();
  motor.positionGain = node.number("gain", motor.positionGain);
  if (!(motor.positionGain > 0.0 && motor.positionGain <= 1.0))
    node.child("gain").fail("must be in (0, 1]");
  return motor;
}

UrdfPlacement parsePlacement(const JsonNode& node, const std::filesystem::path& sceneDirectory) {
  node.allowOnly({"file", "name", "position", "orientation", "base", "on_floor", "q", "motors",
                  "hold", "max_effort", "package_path", "fuse_fixed_joints", "joint_damping",
                  "mimic", "self_collision", "friction", "torques", "coordinates"});
  UrdfPlacement p;
  try {
    p.file = resolveRobotFile(node.child("file").string(), sceneDirectory, "file");
  } catch (const CoulombError& e) {
    node.fail(e.what());
  }
  p.name = node.string("name", p.file.stem().string());
  p.options.basePose.position = node.vector3("position", Eigen::Vector3d::Zero());
  if (node.has("orientation"))
    p.options.basePose.rotation = parseOrientation(node.child("orientation"));
  const std::string base = node.string("base", "fixed");
  if (base == "floating")
    p.options.base = UrdfBase::Floating;
  else if (base != "fixed")
    node.child("base").fail("expected \"fixed\" or \"floating\" (got \"" + base + "\")");
  if (node.has("on_floor")) p.clearance = node.child("on_floor").number();
  if (p.clearance && *p.clearance < 0.0) node.child("on_floor").fail("must be >= 0 m");
  if (node.has("q")) p.q = parseJointValues(node.child("q"));
  if (node.has("motors")) {
    const JsonNode motors = node.child("motors");
    for (const std::string& joint : motors.objectKeys())
      p.motors[joint] = parseMotor(motors.child(joint.c_str()));
  }
  if (node.has("torques")) p.torques = parseJointValues(node.child("torques"));
  if (node.has("hold")) p.holdAllJoints = node.child("hold").raw() == true;
  if (node.has("max_effort")) p.defaultMaxEffort = node.child("max_effort").positiveNumber();
  if (node.has("package_path")) {
    const JsonNode paths = node.child("package_path");
    for (std::size_t i = 0; i < paths.arraySize(); ++i)
      p.options.packagePath.push_back(sceneDirectory / paths.element(i).string());
  }
  if (node.has("fuse_fixed_joints"))
    p.options.fuseFixedJoints = node.child("fuse_fixed_joints").raw() == true;
  if (node.has("joint_damping")) p.options.jointDamping = node.child("joint_damping").raw() == true;
  if (node.has("mimic")) p.mimicCouplings = node.child("mimic").raw() == true;
  if (node.has("self_collision")) p.selfCollision = node.child("self_collision").raw() == true;
  if (node.has("friction")) p.options.defaultFriction = node.child("friction").positiveNumber();
  const std::string coordinates = node.string("coordinates", "reduced");
  if (coordinates == "maximal")
    p.maximal = true;
  else if (coordinates != "reduced")
    node.child("coordinates")
        .fail("expected \"reduced\" or \"maximal\" (got \"" + coordinates + "\")");
  return p;
}

}  // namespace

std::filesystem::path resolveRobotFile(const std::string& file,
                                       const std::filesystem::path& sceneDirectory,
                                       const std::string& where) {
  const std::filesystem::path written(file);
  std::vector<std::filesystem::path> candidates;
  if (written.is_absolute()) {
    candidates.push_back(written);
  } else {
    candidates.push_back(sceneDirectory / written);
    std::filesystem::path withoutParents;  // "../robots/a.urdf" -> "robots/a.urdf"
    for (const auto& part : written)
      if (!(withoutParents.empty() && part == "..")) withoutParents /= part;
    if (const char* env = std::getenv("COULOMB_ROBOT_PATH")) {
      std::stringstream folders(env);
      std::string folder;
      while (std::getline(folders, folder, ':')) {
        if (folder.empty()) continue;
        candidates.push_back(std::filesystem::path(folder) / written);
        if (withoutParents != written)
          candidates.push_back(std::filesystem::path(folder) / withoutParents);
      }
    }
  }
  for (const auto& candidate : candidates)
    if (std::filesystem::is_regular_file(candidate)) return candidate.lexically_normal();
  // Built with append: GCC 12 gives a false -Wrestrict on chained concatenation here.
  std::string message = where;
  message.append(": URDF file '").append(file).append("' not found (tried");
  for (const auto& candidate : candidates) message.append(" ").append(candidate.string());
  message.append("; set COULOMB_ROBOT_PATH to the folder holding it)");
  throw CoulombError(message);
}

namespace {

struct PlacedRobot {
  UrdfModel model;  // the root joints moved by the floor clearance
  ArticulationDesc desc;
};

PlacedRobot place(const UrdfPlacement& placement, const std::string& where) {
  UrdfModel model;
  try {
    model = loadUrdfFile(placement.file, placement.options);
  } catch (const CoulombError& e) {
    throw CoulombError(where.empty() ? std::string(e.what()) : where + ": " + e.what());
  }
  ArticulationDesc desc = toArticulationDesc(model, placement.name);
  desc.selfCollision = placement.selfCollision;
  const joints::tree::Articulation tree = toArticulation(model);
  Eigen::VectorXd q = tree.neutralConfiguration();
  for (const auto& [joint, value] : placement.q)
    q[tree.qIndex(linkOfJoint(model, joint, where + ": q"))] = value;
  desc.q = q;

  auto effortOf = [&](int link, const std::optional<double>& given) {
    if (given) return *given;
    const double limit = model.bodies[static_cast<std::size_t>(link)].effortLimit;
    return limit > 0.0 ? limit : placement.defaultMaxEffort;
  };
  std::vector<bool> driven(model.bodies.size(), false);
  for (const auto& [joint, spec] : placement.motors) {
    const int link = linkOfJoint(model, joint, where + ": motors");
    desc.motors.push_back({link, spec.mode, spec.target, effortOf(link, spec.maxEffort),
                           spec.positionGain, std::numeric_limits<double>::infinity()});
    driven[static_cast<std::size_t>(link)] = true;
  }
  if (placement.holdAllJoints)
    for (std::size_t i = 0; i < model.bodies.size(); ++i)
      if (!driven[i] && model.bodies[i].joint.nv() == 1)
        desc.motors.push_back({static_cast<int>(i), JointMotorMode::Position, q[tree.qIndex(i)],
                               effortOf(static_cast<int>(i), std::nullopt), 0.2,
                               std::numeric_limits<double>::infinity()});
  for (const auto& [joint, torque] : placement.torques)
    desc.jointTorques.push_back({linkOfJoint(model, joint, where + ": torques"), torque});
  if (placement.mimicCouplings)
    for (const UrdfMimic& mimic : model.mimics)
      desc.couplings.push_back({linkOfJoint(model, mimic.joint, where + ": mimic"),
                                linkOfJoint(model, mimic.leader, where + ": mimic"),
                                mimic.multiplier, mimic.offset});

  if (placement.clearance) {  // rest on the floor z = 0: move the root joint up or down
    const double lowest = lowestPoint(desc, model);
    if (std::isfinite(lowest)) {
      const double lift = *placement.clearance - lowest;
      for (ArticulationLinkDesc& link : desc.links)
        if (link.parent < 0) link.joint.parentToJoint.position.z() += lift;
      for (UrdfBody& body : model.bodies)
        if (body.parent < 0) body.joint.parentToJoint.position.z() += lift;
    }
  }
  return {std::move(model), std::move(desc)};
}

}  // namespace

ArticulationDesc placeUrdf(const UrdfPlacement& placement, const std::string& where) {
  return place(placement, where).desc;
}

UrdfMaximal placeUrdfMaximal(const UrdfPlacement& placement, const std::string& where) {
  const std::string prefix = where.empty() ? std::string() : where + ": ";
  PlacedRobot robot = place(placement, where);
  if (!robot.desc.jointTorques.empty())
    throw CoulombError(prefix +
                       "\"torques\" need reduced coordinates (drop \"coordinates\": "
                       "\"maximal\" or the torques)");
  UrdfMaximal out = toMaximal(robot.model, placement.name, robot.desc.q);
  for (const JointMotorDesc& motor : robot.desc.motors) {
    const std::string& joint = robot.model.bodies[static_cast<std::size_t>(motor.link)].joint.name;
    if (motor.mode != JointMotorMode::Velocity)
      throw CoulombError(prefix + "motor on '" + joint +
                         "': maximal-coordinate joints take velocity motors only (\"mode\": "
                         "\"velocity\"; \"hold\" and position targets need reduced coordinates)");
    joints::JointDef& def = out.joints[static_cast<std::size_t>(out.jointIndex.at(joint))].def;
    def.motor = {true, motor.target, motor.maxEffort};
    def.friction = 0.0;  // not combined with a motor (JointDef.hpp)
  }
  return out;
}

UrdfSection parseUrdfSection(const JsonNode& node, const std::filesystem::path& sceneDirectory,
                             const std::map<std::string, double>& materialFriction) {
  UrdfSection robots;
  for (std::size_t i = 0; i < node.arraySize(); ++i) {
    const JsonNode entry = node.element(i);
    UrdfPlacement placement = parsePlacement(entry, sceneDirectory);
    placement.options.materialFriction.insert(materialFriction.begin(), materialFriction.end());
    try {
      if (!placement.maximal) {
        robots.articulations.push_back(placeUrdf(placement, "robot"));
        continue;
      }
      UrdfMaximal maximal = placeUrdfMaximal(placement, "robot");
      const auto offset = static_cast<int>(robots.bodies.size());
      for (UrdfMaximalJoint& j : maximal.joints)
        robots.joints.push_back({j.bodyA < 0 ? -1 : j.bodyA + offset,
                                 j.bodyB < 0 ? -1 : j.bodyB + offset, std::move(j.def)});
      std::move(maximal.bodies.begin(), maximal.bodies.end(), std::back_inserter(robots.bodies));
    } catch (const CoulombError& e) {
      entry.fail(e.what());  // "<scene>: urdf[i]: robot: ..."
    }
  }
  return robots;
}

Scene urdfFileScene(const std::filesystem::path& file, UrdfBase base, bool hold,
                    const std::vector<std::filesystem::path>& packagePath, bool maximal) {
  Scene scene;
  scene.source = file.string();
  scene.name = file.stem().string();
  scene.description = "URDF robot on a floor";
  BodyDesc floor;
  floor.name = "floor";
  floor.motionType = geometry::MotionType::Static;
  ShapeDesc plane{geometry::Plane{}, Pose{}, {}, {}};
  plane.material.friction = 0.8;
  floor.shapes.push_back(plane);
  scene.bodies.push_back(floor);
  UrdfPlacement placement;
  placement.file = file;
  placement.name = file.stem().string();
  placement.options.base = base;
  placement.options.packagePath = packagePath;
  placement.clearance = base == UrdfBase::Floating ? 0.05 : 0.0;
  placement.holdAllJoints = hold;
  if (!maximal) {
    scene.articulations.push_back(placeUrdf(placement, ""));  // loader errors name the file
    return scene;
  }
  if (hold)
    throw CoulombError(file.string() +
                       ": maximal coordinates cannot hold the joints (position motors need the "
                       "tree); add --limp");
  UrdfMaximal robot = placeUrdfMaximal(placement, "");
  for (UrdfMaximalJoint& j : robot.joints)  // after the floor: body indices shift by one
    scene.joints.push_back({j.bodyA < 0 ? -1 : j.bodyA + 1, j.bodyB + 1, std::move(j.def)});
  std::move(robot.bodies.begin(), robot.bodies.end(), std::back_inserter(scene.bodies));
  return scene;
}

}  // namespace coulomb::engine::io
