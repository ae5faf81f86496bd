#include <coulomb/io/JsonReader.hpp>
#include <coulomb/io/UrdfReport.hpp>
#include <coulomb/joints/tree/TreeDynamics.hpp>

#include <nlohmann/json.hpp>

#include <cmath>
#include <iomanip>
#include <map>
#include <sstream>
#include <vector>

namespace coulomb::engine::io {
namespace {

using json = nlohmann::ordered_json;  // keys in the documented order

json limitValue(double value) {
  return std::isfinite(value) ? json(value) : json(nullptr);
}

json vectorJson(const Eigen::VectorXd& v) {
  json out = json::array();
  for (Eigen::Index i = 0; i < v.size(); ++i) out.push_back(v[i]);
  return out;
}

json bodyJson(const UrdfModel& model, const UrdfBody& body) {
  const Eigen::Matrix3d& inertia = body.inertia.inertiaAboutCom;
  json collisions = json::array();
  for (const UrdfCollision& c : body.collisions)
    collisions.push_back(
        {{"shape", c.description}, {"link", c.link}, {"friction", c.material.friction}});
  return {
      {"name", body.name},
      {"parent", body.parent < 0 ? json(nullptr)
                                 : json(model.bodies[static_cast<std::size_t>(body.parent)].name)},
      {"joint",
       {{"name", body.joint.name},
        {"type", joints::tree::toString(body.joint.type)},
        {"axis", vectorJson(body.joint.axis)},
        {"lower", limitValue(body.joint.lower)},
        {"upper", limitValue(body.joint.upper)},
        {"damping", body.joint.damping},
        {"friction", body.jointFriction}}},
      {"mass", body.inertia.mass},
      {"com", vectorJson(body.inertia.centerOfMass)},
      {"inertia_about_com",
       {inertia(0, 0), inertia(1, 1), inertia(2, 2), inertia(0, 1), inertia(0, 2), inertia(1, 2)}},
      {"inertia_valid", body.inertiaValid},
      {"inertia", toString(body.inertiaStatus)},
      {"fused_links", body.fusedLinks},
      {"collisions", collisions},
      {"skipped_meshes", body.skippedMeshes}};
}

json countsJson(const std::map<std::string, int>& counts) {
  json out = json::object();
  for (const auto& [name, count] : counts) out[name] = count;
  return out;
}

/// "kd x12, kp x12, plugin x2": element names with their counts, in name order.
std::string countsText(const std::map<std::string, int>& counts) {
  std::ostringstream out;
  for (const auto& [name, count] : counts)
    out << (out.tellp() > 0 ? ", " : "") << name << " x" << count;
  return out.str();
}

void gazeboText(const UrdfGazeboUse& gazebo, std::ostream& out) {
  if (gazebo.blocks == 0) return;
  out << "\ngazebo extensions (" << gazebo.blocks << " <gazebo> blocks):\n";
  out << "  used: " << (gazebo.used.empty() ? "nothing" : countsText(gazebo.used)) << "\n";
  if (!gazebo.friction.empty()) {
    out << "  friction (mu1) of " << gazebo.friction.size() << " link(s):";
    for (const auto& [link, mu] : gazebo.friction) out << " " << link << " " << mu;
    out << "\n";
  }
  out << "  ignored: " << (gazebo.ignored.empty() ? "nothing" : countsText(gazebo.ignored)) << "\n";
}

const char* inertiaText(UrdfInertiaStatus status) {
  switch (status) {
    case UrdfInertiaStatus::Physical:
      return "valid";
    case UrdfInertiaStatus::PointMass:
      return "point mass";
    case UrdfInertiaStatus::Massless:
      return "massless";
    case UrdfInertiaStatus::AsWritten:
      return "as written, not physical (see warnings)";
    case UrdfInertiaStatus::Repaired:
      return "repaired (see warnings)";
  }
  return "?";
}

int velocityCount(const UrdfModel& model) {
  int nv = 0;
  for (const UrdfBody& body : model.bodies) nv += body.joint.nv();
  return nv;
}

}  // namespace

UrdfOptions urdfDynamicsOptions(UrdfOptions options) {
  options.base = UrdfBase::Fixed;
  options.jointDamping = false;  // pure rigid-body dynamics, as other tools' M, h and ABA
  options.loadCollisionMeshes = false;
  return options;
}

UrdfJointState parseUrdfJointState(const std::string& text, const std::string& source,
                                   const UrdfModel& model) {
  nlohmann::json document;  // JsonNode reads nlohmann::json (not the ordered output type)
  try {
    document = nlohmann::json::parse(text);
  } catch (const nlohmann::json::exception& e) {  // parse_error, or out_of_range (1e999)
    throw CoulombError(source + ": not valid JSON (" + e.what() + ")");
  }
  const JsonNode root(document, source, "");
  if (!document.is_object()) root.fail("must be an object {\"q\": {...}, ...}");
  root.allowOnly({"q", "qdot", "tau", "gravity"});
  const auto n = static_cast<Eigen::Index>(model.dofNames.size());
  UrdfJointState state{Eigen::VectorXd::Zero(n), Eigen::VectorXd::Zero(n), Eigen::VectorXd::Zero(n),
                       model.gravity};
  for (const auto& [key, target] :
       {std::pair{"q", &state.q}, std::pair{"qdot", &state.qdot}, std::pair{"tau", &state.tau}}) {
    if (!root.has(key)) continue;
    const JsonNode values = root.child(key);
    for (const std::string& joint : values.objectKeys()) {
      const auto it = std::find(model.dofNames.begin(), model.dofNames.end(), joint);
      if (it == model.dofNames.end()) {
        const auto near = nearestName(joint, model.dofNames);
        values.fail("no moving joint named '" + joint + "'" +
                    (near ? " (did you mean '" + *near + "'?)" : ""));
      }
      (*target)[it - model.dofNames.begin()] = values.child(joint.c_str()).number();
    }
  }
  if (root.has("gravity")) state.gravity = root.child("gravity").vector3();
  return state;
}

std::string urdfDynamicsJson(const UrdfModel& model, const UrdfJointState& state) {
  if (velocityCount(model) != model.dofCount())
    throw CoulombError(model.file +
                       ": dynamics by joint name needs 1-DOF joints and a fixed base (this model "
                       "has a floating joint)");
  UrdfModel withGravity = model;
  withGravity.gravity = state.gravity;
  const joints::tree::Articulation tree = toArticulation(withGravity);
  Eigen::VectorXd qdd;
  try {
    qdd = joints::tree::forwardDynamics(tree, state.q, state.qdot, state.tau);
  } catch (const std::exception& e) {
    throw CoulombError(model.file + ": " + e.what());
  }
  const Eigen::MatrixXd mass = joints::tree::massMatrix(tree, state.q);
  json rows = json::array();
  for (Eigen::Index i = 0; i < mass.rows(); ++i)
    rows.push_back(vectorJson(mass.row(i).transpose()));
  // The numbers are the file's, so that they can be checked against another tool: say where
  // they are not (docs/urdf.md, "Inertia policy").
  std::vector<std::string> repaired, notPhysical;
  for (const UrdfBody& body : model.bodies) {
    if (body.inertiaStatus == UrdfInertiaStatus::Repaired) repaired.push_back(body.name);
    if (body.inertiaStatus == UrdfInertiaStatus::AsWritten) notPhysical.push_back(body.name);
  }
  const json out = {
      {"joints", model.dofNames},
      {"qddot", vectorJson(qdd)},
      {"mass_matrix", rows},
      {"bias_forces", vectorJson(joints::tree::biasForces(tree, state.q, state.qdot))},
      {"inertias",
       {{"as_written", repaired.empty()},
        {"repaired", repaired},
        {"not_physical_kept", notPhysical}}}};
  return out.dump() + "\n";
}

std::string urdfInfoJson(const UrdfModel& model) {
  json bodies = json::array();
  for (const UrdfBody& body : model.bodies) bodies.push_back(bodyJson(model, body));
  json mimics = json::array();
  for (const UrdfMimic& m : model.mimics)
    mimics.push_back({{"joint", m.joint},
                      {"leader", m.leader},
                      {"multiplier", m.multiplier},
                      {"offset", m.offset}});
  const json out = {{"file", model.file},
                    {"robot", model.robotName},
                    {"urdf_links", model.urdfLinkCount},
                    {"urdf_joints", model.urdfJointCount},
                    {"floating_base", model.floatingBase},
                    {"dofs", velocityCount(model)},
                    {"joints", model.dofNames},
                    {"total_mass", model.totalMass()},
                    {"bodies", bodies},
                    {"mimics", mimics},
                    {"gazebo",
                     {{"blocks", model.gazebo.blocks},
                      {"friction", model.gazebo.friction},
                      {"used", countsJson(model.gazebo.used)},
                      {"ignored", countsJson(model.gazebo.ignored)}}},
                    {"warnings", model.warnings}};
  return out.dump(2) + "\n";
}

std::string urdfInfoText(const UrdfModel& model) {
  std::ostringstream out;
  out << std::setprecision(6);
  out << model.file << ": robot '" << model.robotName << "', " << model.urdfLinkCount << " links, "
      << model.urdfJointCount << " joints -> " << model.bodies.size()
      << " bodies (fixed joints fused), " << velocityCount(model) << " DOFs"
      << (model.floatingBase ? " (floating base)" : " (fixed base)") << ", total mass "
      << model.totalMass() << " kg\n";
  out << "joints in DOF order:";
  for (const std::string& name : model.dofNames) out << " " << name;
  out << "\n\nbodies:\n";
  for (std::size_t i = 0; i < model.bodies.size(); ++i) {
    const UrdfBody& b = model.bodies[i];
    out << "  [" << i << "] " << b.name << "  <- "
        << (b.parent < 0 ? std::string("world")
                         : model.bodies[static_cast<std::size_t>(b.parent)].name)
        << " by " << joints::tree::toString(b.joint.type) << " '" << b.joint.name << "'";
    if (b.joint.nv() == 1) out << " axis (" << b.joint.axis.transpose() << ")";
    if (std::isfinite(b.joint.lower)) out << " [" << b.joint.lower << ", " << b.joint.upper << "]";
    out << "\n      mass " << b.inertia.mass << " kg, inertia " << inertiaText(b.inertiaStatus)
        << ", " << b.collisions.size() << " collision shape(s)";
    if (!b.skippedMeshes.empty()) out << " (+" << b.skippedMeshes.size() << " meshes not loaded)";
    out << "\n";
    if (!b.fusedLinks.empty()) {
      out << "      fused:";
      for (const std::string& link : b.fusedLinks) out << " " << link;
      out << "\n";
    }
    for (const UrdfCollision& c : b.collisions) out << "      - " << c.description << "\n";
  }
  if (!model.mimics.empty()) {
    out << "\nmimic couplings (not enforced yet):\n";
    for (const UrdfMimic& m : model.mimics)
      out << "  " << m.joint << " = " << m.multiplier << " * " << m.leader << " + " << m.offset
          << "\n";
  }
  gazeboText(model.gazebo, out);
  out << "\nwarnings (" << model.warnings.size() << "):\n";
  for (const std::string& w : model.warnings) out << "  - " << w << "\n";
  return out.str();
}

}  // namespace coulomb::engine::io
