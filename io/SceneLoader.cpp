#include <coulomb/io/JointJson.hpp>
#include <coulomb/io/JsonReader.hpp>
#include <coulomb/io/SceneLoader.hpp>
#include <coulomb/io/SolverSection.hpp>
#include <coulomb/io/UrdfScene.hpp>

#include <coulomb/meshes/MakeConvexHull.hpp>
#include <coulomb/meshes/MeshLoader.hpp>

#include <algorithm>
#include <fstream>
#include <iterator>
#include <map>
#include <sstream>

namespace coulomb::engine::io {
namespace {

using geometry::MotionType;
using geometry::Pose;
using Materials = std::map<std::string, geometry::Material>;

geometry::Material parseMaterial(const JsonNode& node) {
  node.allowOnly({"friction", "restitution"});
  geometry::Material m;
  m.friction = node.number("friction", m.friction);
  m.restitution = node.number("restitution", m.restitution);
  if (m.friction < 0.0) node.child("friction").fail("must be >= 0");
  if (m.restitution < 0.0 || m.restitution > 1.0)
    node.child("restitution").fail("must be in [0, 1]");
  return m;
}

// [w, x, y, z] or {"axis": [x, y, z], "angle": radians}.
Pose parsePose(const JsonNode& node) {
  Pose pose;
  pose.position = node.vector3("position", Eigen::Vector3d::Zero());
  if (node.has("orientation")) pose.rotation = parseOrientation(node.child("orientation"));
  return pose;
}

std::vector<Eigen::Vector3d> parsePoints(const JsonNode& node) {
  std::vector<Eigen::Vector3d> points(node.arraySize());
  for (std::size_t i = 0; i < points.size(); ++i) points[i] = node.element(i).vector3();
  return points;
}

geometry::TriangleMesh parseMesh(const JsonNode& node, const std::filesystem::path& base) {
  if (node.has("file")) {
    if (node.has("vertices") || node.has("triangles"))
      node.fail("give either \"file\" or \"vertices\" + \"triangles\", not both");
    const std::filesystem::path file = base / node.child("file").string();
    const Eigen::Vector3d scale = node.vector3("scale", Eigen::Vector3d::Ones());
    try {
      return geometry::loadTriangleMesh(file.string(), scale);
    } catch (const std::exception& e) {
      node.child("file").fail(e.what());
    }
  }
  geometry::TriangleMesh mesh;
  mesh.vertices = parsePoints(node.child("vertices"));
  const JsonNode triangles = node.child("triangles");
  for (std::size_t i = 0; i < triangles.arraySize(); ++i)
    mesh.triangles.push_back(triangles.element(i).index3());
  return mesh;
}

ShapeDesc parseShape(const JsonNode& node, const Materials& materials,
                     const std::filesystem::path& base) {
  if (!node.raw().is_object()) node.fail("expected a shape object with a \"type\"");
  const std::string type = node.child("type").string();
  static const std::vector<std::string> kTypes = {"sphere", "box",         "capsule", "cylinder",
                                                  "plane",  "convex_hull", "mesh"};
  // Unknown keys are errors; the allowed set depends on the type.
  auto allow = [&](std::initializer_list<const char*> specific) {
    std::vector<std::string> names = {"type",     "position", "orientation",
                                      "material", "filter",   "sensor"};
    names.insert(names.end(), specific.begin(), specific.end());
    for (const auto& [key, unused] : node.raw().items()) {
      if (std::find(names.begin(), names.end(), key) != names.end()) continue;
      std::string message = "unknown key '" + key + "' for a " + type;
      if (auto s = nearestName(key, names)) message += "; did you mean '" + *s + "'?";
      node.child(key.c_str()).fail(message);
    }
  };
  ShapeDesc desc;
  if (type == "sphere") {
    allow({"radius"});
    desc.shape = geometry::Sphere{node.child("radius").positiveNumber()};
  } else if (type == "box") {
    allow({"half_extents"});
    desc.shape = geometry::Box{node.child("half_extents").vector3()};
  } else if (type == "capsule" || type == "cylinder") {
    allow({"radius", "half_length"});
    const double r = node.child("radius").positiveNumber();
    const double h = node.child("half_length").number();
    if (type == "capsule")
      desc.shape = geometry::Capsule{r, h};
    else
      desc.shape = geometry::Cylinder{r, h};
  } else if (type == "plane") {
    allow({"normal", "offset"});
    desc.shape = geometry::Plane{node.vector3("normal", Eigen::Vector3d::UnitZ()),
                                 node.number("offset", 0.0)};
  } else if (type == "convex_hull") {
    allow({"points"});
    geometry::ConvexHull hull;
    hull.vertices = parsePoints(node.child("points"));
    desc.shape = std::move(hull);
  } else if (type == "mesh") {
    allow({"file", "scale", "vertices", "triangles"});
    desc.shape = parseMesh(node, base);
  } else {
    std::string message = "unknown shape type '" + type + "'";
    if (auto s = nearestName(type, kTypes)) message += "; did you mean '" + *s + "'?";
    node.child("type").fail(message);
  }
  if (auto problem = geometry::validateShape(desc.shape)) node.fail(*problem);
  // Hulls given as points get their faces here (qhull, component meshes): the core takes hulls
  // with faces only.
  if (auto* hull = std::get_if<geometry::ConvexHull>(&desc.shape);
      hull && hull->triangles.empty()) {
    try {
      *hull = geometry::makeConvexHull(hull->vertices);
    } catch (const std::invalid_argument& e) {
      node.fail(std::string("convex_hull: ") + e.what());
    }
  }
  desc.localPose = parsePose(node);
  if (node.has("material")) {
    const JsonNode m = node.child("material");
    if (m.raw().is_string()) {
      const std::string name = m.string();
      const auto found = materials.find(name);
      if (found == materials.end()) {
        std::vector<std::string> names;
        for (const auto& [n, unused] : materials) names.push_back(n);
        std::string message = "unknown material '" + name + "'";
        if (auto s = nearestName(name, names))
          message += "; did you mean '" + *s + "'?";
        else
          message += " (define it under \"materials\")";
        m.fail(message);
      }
      desc.material = found->second;
    } else {
      desc.material = parseMaterial(m);
    }
  }
  if (node.has("filter")) {
    const JsonNode f = node.child("filter");
    f.allowOnly({"category", "mask"});
    auto bits = [&](const char* key, std::uint32_t fallback) -> std::uint32_t {
      if (!f.has(key)) return fallback;
      const std::uint64_t value = f.child(key).unsignedInteger();
      if (value > 0xffffffffu) f.child(key).fail("must fit in 32 bits");
      return static_cast<std::uint32_t>(value);
    };
    desc.filter.category = bits("category", desc.filter.category);
    desc.filter.mask = bits("mask", desc.filter.mask);
  }
  if (node.has("sensor")) desc.sensor = node.child("sensor").boolean();
  return desc;
}

MotionType parseMotionType(const JsonNode& node) {
  const std::string type = node.string();
  if (type == "static") return MotionType::Static;
  if (type == "kinematic") return MotionType::Kinematic;
  if (type == "dynamic") return MotionType::Dynamic;
  std::string message = "unknown body type '" + type + "'";
  if (auto s = nearestName(type, {"static", "kinematic", "dynamic"}))
    message += "; did you mean '" + *s + "'?";
  node.fail(message);
}

Eigen::Matrix3d parseInertia(const JsonNode& node) {
  // [Ixx, Iyy, Izz] (principal, body axes) or a 3x3 matrix [[..], [..], [..]].
  if (node.arraySize() == 3 && node.raw()[0].is_number()) return node.vector3().asDiagonal();
  Eigen::Matrix3d inertia;
  if (node.arraySize() != 3) node.fail("expected [Ixx, Iyy, Izz] or a 3x3 matrix");
  for (int r = 0; r < 3; ++r) inertia.row(r) = node.element(static_cast<std::size_t>(r)).vector3();
  return inertia;
}

BodyDesc parseBody(const JsonNode& node, const Materials& materials,
                   const std::filesystem::path& base) {
  node.allowOnly({"name", "type", "position", "orientation", "linear_velocity", "angular_velocity",
                  "density", "mass", "inertia", "center_of_mass", "shapes", "solver",
                  "continuous_collision"});
  BodyDesc desc;
  desc.name = node.string("name", "");
  if (node.has("continuous_collision"))
    desc.continuousCollision = node.child("continuous_collision").boolean();
  if (node.has("solver")) desc.solver = parseSolverRequest(node.child("solver"));
  if (node.has("type")) desc.motionType = parseMotionType(node.child("type"));
  desc.pose = parsePose(node);
  desc.linearVelocity = node.vector3("linear_velocity", Eigen::Vector3d::Zero());
  desc.angularVelocity = node.vector3("angular_velocity", Eigen::Vector3d::Zero());
  if (node.has("density")) {
    if (node.has("mass"))
      node.child("density").fail("give either \"density\" or \"mass\", not both");
    desc.density = node.child("density").positiveNumber();
  }
  if (node.has("mass")) {
    if (!node.has("inertia")) node.fail("\"inertia\" is required when \"mass\" is given");
    geometry::SpatialInertia mass;
    mass.mass = node.child("mass").positiveNumber();
    mass.inertiaAboutCom = parseInertia(node.child("inertia"));
    mass.centerOfMass = node.vector3("center_of_mass", Eigen::Vector3d::Zero());
    if (auto problem = geometry::checkPhysicalValidity(mass)) node.child("inertia").fail(*problem);
    desc.mass = mass;
  } else {
    for (const char* key : {"inertia", "center_of_mass"})
      if (node.has(key)) node.child(key).fail("only allowed together with \"mass\"");
  }
  if (node.has("shapes")) {
    const JsonNode shapes = node.child("shapes");
    for (std::size_t k = 0; k < shapes.arraySize(); ++k)
      desc.shapes.push_back(parseShape(shapes.element(k), materials, base));
  }
  return desc;
}

// --- articulations (docs/scene-format.md "articulations") ---------------------------------

joints::tree::TreeJoint parseTreeJoint(const JsonNode& node, const std::string& linkName) {
  using joints::tree::TreeJoint;
  node.allowOnly(
      {"type", "name", "position", "orientation", "axis", "lower", "upper", "damping", "armature"});
  const std::string type = node.string("type", "revolute");
  const std::string name = node.string("name", linkName);
  const Pose pose = parsePose(node);
  Eigen::Vector3d axis = node.vector3("axis", Eigen::Vector3d::UnitZ());
  if (axis.norm() < 1e-12) node.child("axis").fail("must be non-zero");
  axis.normalize();
  TreeJoint joint;
  if (type == "revolute")
    joint = TreeJoint::revolute(name, pose, axis);
  else if (type == "continuous")
    joint = TreeJoint::continuous(name, pose, axis);
  else if (type == "prismatic")
    joint = TreeJoint::prismatic(name, pose, axis);
  else if (type == "fixed")
    joint = TreeJoint::fixed(name, pose);
  else if (type == "spherical")
    joint = TreeJoint::spherical(name, pose);
  else if (type == "floating")
    joint = TreeJoint::floating(name, pose);
  else {
    std::string message = "unknown joint type '" + type + "'";
    if (auto s = nearestName(
            type, {"revolute", "continuous", "prismatic", "fixed", "spherical", "floating"}))
      message += "; did you mean '" + *s + "'?";
    node.child("type").fail(message);
  }
  joint.lower = node.number("lower", joint.lower);
  joint.upper = node.number("upper", joint.upper);
  if (joint.lower > joint.upper) node.fail("\"lower\" must be <= \"upper\"");
  joint.damping = node.number("damping", 0.0);
  joint.armature = node.number("armature", 0.0);
  if (joint.damping < 0.0) node.child("damping").fail("must be >= 0");
  if (joint.armature < 0.0) node.child("armature").fail("must be >= 0");
  return joint;
}

/// Index of the link named by `node` ("world" = -1) among `names`.
int linkIndex(const JsonNode& node, const std::vector<std::string>& names) {
  const std::string name = node.string();
  if (name == "world") return -1;
  const auto found = std::find(names.begin(), names.end(), name);
  if (found == names.end()) {
    std::string message = "unknown link '" + name + "' (links are named before they are used)";
    if (auto s = nearestName(name, names)) message += "; did you mean '" + *s + "'?";
    node.fail(message);
  }
  return static_cast<int>(found - names.begin());
}

Eigen::VectorXd parseVector(const JsonNode& node) {
  Eigen::VectorXd v(static_cast<Eigen::Index>(node.arraySize()));
  for (std::size_t i = 0; i < node.arraySize(); ++i)
    v[static_cast<Eigen::Index>(i)] = node.element(i).number();
  return v;
}

ArticulationDesc parseArticulation(const JsonNode& node, const Materials& materials,
                                   const std::filesystem::path& base) {
  node.allowOnly(
      {"name", "links", "q", "qd", "self_collision", "error_reduction", "loop_closures"});
  ArticulationDesc desc;
  desc.name = node.string("name", "articulation");
  std::vector<std::string> names;
  const JsonNode links = node.child("links");
  for (std::size_t i = 0; i < links.arraySize(); ++i) {
    const JsonNode l = links.element(i);
    l.allowOnly(
        {"name", "parent", "joint", "density", "mass", "inertia", "center_of_mass", "shapes"});
    ArticulationLinkDesc link;
    link.name = l.string("name", "link" + std::to_string(i));
    link.parent = l.has("parent") ? linkIndex(l.child("parent"), names) : -1;
    link.joint = parseTreeJoint(l.child("joint"), link.name);
    if (l.has("density")) link.density = l.child("density").positiveNumber();
    if (l.has("mass")) {
      if (!l.has("inertia")) l.fail("\"inertia\" is required when \"mass\" is given");
      geometry::SpatialInertia mass;
      mass.mass = l.child("mass").positiveNumber();
      mass.inertiaAboutCom = parseInertia(l.child("inertia"));
      mass.centerOfMass = l.vector3("center_of_mass", Eigen::Vector3d::Zero());
      if (auto problem = geometry::checkPhysicalValidity(mass)) l.child("inertia").fail(*problem);
      link.inertia = mass;
    }
    if (l.has("shapes")) {
      const JsonNode shapes = l.child("shapes");
      for (std::size_t k = 0; k < shapes.arraySize(); ++k)
        link.shapes.push_back(parseShape(shapes.element(k), materials, base));
    }
    names.push_back(link.name);
    desc.links.push_back(std::move(link));
  }
  if (node.has("q")) desc.q = parseVector(node.child("q"));
  if (node.has("qd")) desc.qd = parseVector(node.child("qd"));
  if (node.has("self_collision")) desc.selfCollision = node.child("self_collision").raw() == true;
  desc.errorReduction = node.number("error_reduction", desc.errorReduction);
  if (node.has("loop_closures")) {
    const JsonNode closures = node.child("loop_closures");
    for (std::size_t k = 0; k < closures.arraySize(); ++k) {
      const JsonNode c = closures.element(k);
      c.allowOnly({"link_a", "anchor_a", "link_b", "anchor_b", "axes"});
      LoopClosureDesc closure;
      closure.linkA = linkIndex(c.child("link_a"), names);
      if (closure.linkA < 0) c.child("link_a").fail("must be a link (\"world\" only as link_b)");
      closure.anchorA = c.vector3("anchor_a", Eigen::Vector3d::Zero());
      closure.linkB = c.has("link_b") ? linkIndex(c.child("link_b"), names) : -1;
      closure.anchorB = c.vector3("anchor_b", Eigen::Vector3d::Zero());
      const std::string axes = c.string("axes", "xyz");
      closure.axes = {axes.find('x') != std::string::npos, axes.find('y') != std::string::npos,
                      axes.find('z') != std::string::npos};
      if (axes.empty() || axes.find_first_not_of("xyz") != std::string::npos)
        c.child("axes").fail("expected a subset of \"xyz\" (got \"" + axes + "\")");
      desc.loopClosures.push_back(closure);
    }
  }
  return desc;
}

// Sections reserved for later issues: accepted when empty, refused (not silently ignored) when
// they hold anything the engine cannot honour yet.
[[maybe_unused]] void checkReserved(const JsonNode& root, const char* key, const char* what) {
  if (!root.has(key)) return;
  const JsonNode node = root.child(key);
  if (!node.raw().empty())
    node.fail(std::string(what) + " are not supported yet (reserved for a later issue)");
}

// Body keys the World's messages may start with (they then continue the JSON path).
constexpr const char* kBodyFields[] = {"position",         "orientation",    "linear_velocity",
                                       "angular_velocity", "density",        "mass",
                                       "inertia",          "center_of_mass", "shapes"};

}  // namespace

Scene parseScene(std::string_view text, const std::string& source,
                 const std::filesystem::path& baseDirectory) {
  nlohmann::json document;
  try {
    document = nlohmann::json::parse(text.begin(), text.end());
  } catch (const nlohmann::json::exception& e) {  // parse_error, or out_of_range (1e999)
    throw CoulombError(source + ": invalid JSON: " + e.what());
  }
  const JsonNode root(document, source, "");
  root.allowOnly({"name", "description", "gravity", "time_step", "steps", "materials", "bodies",
                  "joints", "joint_stabilization", "solver", "sleep", "urdf", "articulations",
                  "tree_integrator", "threads"});
  Scene scene;
  scene.source = source;
  scene.name = root.string("name", std::filesystem::path(source).stem().string());
  scene.description = root.string("description", "");
  scene.settings.gravity = root.vector3("gravity", scene.settings.gravity);
  if (root.has("time_step")) scene.settings.timeStep = root.child("time_step").positiveNumber();
  if (root.has("steps")) scene.steps = root.child("steps").unsignedInteger();
  if (root.has("tree_integrator")) {  // docs/scene-format.md, docs/tuning.md "Tree integrators"
    const JsonNode node = root.child("tree_integrator");
    const std::string name = node.string();
    if (name == "runge_kutta")
      scene.settings.treeIntegrator = TreeIntegrator::RungeKutta;
    else if (name == "semi_implicit_euler")
      scene.settings.treeIntegrator = TreeIntegrator::SemiImplicitEuler;
    else
      node.fail("must be \"runge_kutta\" or \"semi_implicit_euler\" (got \"" + name + "\")");
  }
  if (root.has("threads")) {  // docs/scene-format.md, docs/embedding.md "Threads"
    const JsonNode node = root.child("threads");
    if (node.raw().is_string()) {
      if (node.string() != "hardware")
        node.fail("must be a thread count >= 1 or \"hardware\" (got \"" + node.string() + "\")");
      scene.settings.threads = 0;
    } else {
      const std::uint64_t count = node.unsignedInteger();
      if (count < 1 || count > static_cast<std::uint64_t>(WorldSettings::kMaxThreads))
        node.fail("must be a thread count in 1.." + std::to_string(WorldSettings::kMaxThreads) +
                  " or \"hardware\" (got " + std::to_string(count) + ")");
      scene.settings.threads = static_cast<int>(count);
    }
  }
  if (root.has("solver")) parseSolverSection(root.child("solver"), scene.settings);
  if (root.has("sleep")) parseSleepSection(root.child("sleep"), scene.settings.sleep);

  Materials materials;
  if (root.has("materials")) {
    const JsonNode node = root.child("materials");
    for (const std::string& name : node.objectKeys())
      materials[name] = parseMaterial(node.child(name.c_str()));
  }
  // A scene of trees alone (articulations, urdf) needs no bodies.
  if (root.has("bodies") || (!root.has("articulations") && !root.has("urdf"))) {
    const JsonNode bodies = root.child("bodies");
    for (std::size_t i = 0; i < bodies.arraySize(); ++i)
      scene.bodies.push_back(parseBody(bodies.element(i), materials, baseDirectory));
  }
  if (root.has("articulations")) {
    const JsonNode articulations = root.child("articulations");
    for (std::size_t i = 0; i < articulations.arraySize(); ++i)
      scene.articulations.push_back(
          parseArticulation(articulations.element(i), materials, baseDirectory));
  }
  if (root.has("urdf")) {  // robots after the articulations (docs/scene-format.md "urdf")
    std::map<std::string, double> friction;  // scene materials for the URDF visual materials
    for (const auto& [name, material] : materials) friction[name] = material.friction;
    UrdfSection robots = parseUrdfSection(root.child("urdf"), baseDirectory, friction);
    std::move(robots.articulations.begin(), robots.articulations.end(),
              std::back_inserter(scene.articulations));
    const auto offset = static_cast<int>(scene.bodies.size());  // maximal robots: bodies, joints
    for (SceneJoint& j : robots.joints)
      scene.joints.push_back({j.bodyA < 0 ? -1 : j.bodyA + offset,
                              j.bodyB < 0 ? -1 : j.bodyB + offset, std::move(j.def)});
    std::move(robots.bodies.begin(), robots.bodies.end(), std::back_inserter(scene.bodies));
  }
  if (root.has("joint_stabilization"))
    scene.settings.jointStabilization =
        parseStabilization(root.child("joint_stabilization"), scene.settings.jointStabilization);
  if (root.has("joints")) {  // after the bodies: joints name them
    const JsonNode joints = root.child("joints");
    for (std::size_t i = 0; i < joints.arraySize(); ++i)
      scene.joints.push_back(
          parseJoint(joints.element(i), scene.bodies, scene.settings.jointStabilization));
  }
  return scene;
}

Scene loadSceneFile(const std::filesystem::path& file) {
  std::ifstream in(file);
  if (!in) throw CoulombError(file.string() + ": cannot open the scene file");
  std::ostringstream text;
  text << in.rdbuf();
  return parseScene(text.str(), file.string(), file.parent_path());
}

World buildWorld(const Scene& scene) {
  World world(scene.settings);
  std::vector<geometry::BodyId> ids;
  for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
    try {
      ids.push_back(world.createBody(scene.bodies[i]));
    } catch (const CoulombError& e) {
      // The World says "body 'name': <field> ..."; re-anchor it at the body's JSON path.
      std::string message = e.what();
      const std::string bodyPrefix = scene.bodies[i].name.empty()
                                         ? std::string("body: ")
                                         : "body '" + scene.bodies[i].name + "': ";
      if (message.rfind(bodyPrefix, 0) == 0) message = message.substr(bodyPrefix.size());
      const bool startsWithField =
          std::any_of(std::begin(kBodyFields), std::end(kBodyFields),
                      [&](const char* field) { return message.rfind(field, 0) == 0; });
      throw CoulombError(scene.source + ": bodies[" + std::to_string(i) + "]" +
                         (startsWithField ? "." : ": ") + message);
    }
  }
  for (std::size_t i = 0; i < scene.articulations.size(); ++i) {
    try {
      world.createArticulation(scene.articulations[i]);
    } catch (const CoulombError& e) {
      throw CoulombError(scene.source + ": articulations[" + std::to_string(i) + "]: " + e.what());
    }
  }
  for (std::size_t i = 0; i < scene.joints.size(); ++i) {
    const SceneJoint& joint = scene.joints[i];
    joints::JointDef def = joint.def;
    const auto id = [&](int body) {
      return body < 0 ? geometry::BodyId{} : ids[static_cast<std::size_t>(body)];
    };
    def.bodyA = id(joint.bodyA);
    def.bodyB = id(joint.bodyB);
    try {
      world.createJoint(def);
    } catch (const CoulombError& e) {
      throw CoulombError(scene.source + ": joints[" + std::to_string(i) + "]: " + e.what());
    }
  }
  return world;
}

}  // namespace coulomb::engine::io
