// URDF -> UrdfModel: urdfdom reads links, inertials and joints; UrdfXml (a TinyXML pass) checks
// the file first and supplies document order, line numbers and every collision element; fixed
// joints are fused, then the policies of docs/urdf.md (inertia, limits, axes, mimic) apply.
#include <coulomb/urdf/UrdfCollisions.hpp>
#include <coulomb/urdf/UrdfInertia.hpp>
#include <coulomb/urdf/UrdfLoader.hpp>
#include <coulomb/urdf/UrdfXml.hpp>

#include <console_bridge/console.h>
#include <urdf_parser/urdf_parser.h>

#include <fstream>
#include <functional>
#include <mutex>
#include <queue>
#include <set>
#include <sstream>

namespace coulomb::engine::io {
namespace {

namespace fs = std::filesystem;
using geometry::Pose;
using geometry::SpatialInertia;
using joints::tree::TreeJoint;

/// Collects urdfdom's console_bridge messages (it reports through them only) instead of
/// printing them. console_bridge's handler is process-wide, hence the lock.
class UrdfdomMessages : public console_bridge::OutputHandler {
 public:
  void log(const std::string& text, console_bridge::LogLevel level, const char*, int) override {
    if (level >= console_bridge::CONSOLE_BRIDGE_LOG_WARN) messages.push_back(text);
  }
  std::vector<std::string> messages;
};

urdf::ModelInterfaceSharedPtr parseWithUrdfdom(const std::string& text,
                                               std::vector<std::string>& messages) {
  static std::mutex handlerLock;  // console_bridge's output handler is a process-wide setting
  const std::lock_guard<std::mutex> guard(handlerLock);
  UrdfdomMessages handler;
  console_bridge::useOutputHandler(&handler);
  urdf::ModelInterfaceSharedPtr model;
  try {
    model = urdf::parseURDF(text);
  } catch (const std::exception& e) {
    handler.messages.push_back(e.what());
  }
  console_bridge::restorePreviousOutputHandler();
  messages = std::move(handler.messages);
  return model;
}

Pose poseOf(const urdf::Pose& p) {
  return {Eigen::Quaterniond(p.rotation.w, p.rotation.x, p.rotation.y, p.rotation.z).normalized(),
          Eigen::Vector3d(p.position.x, p.position.y, p.position.z)};
}

/// Masses add; two massless parts keep the sum of their rotational inertias (operator+ would
/// drop them).
SpatialInertia combine(const SpatialInertia& a, const SpatialInertia& b) {
  if (a.mass + b.mass > 0.0) return a + b;
  return {0.0, Eigen::Vector3d::Zero(), a.inertiaAboutCom + b.inertiaAboutCom};
}

std::string joinNames(const std::vector<std::string>& names, std::size_t limit = 12) {
  std::string out;
  for (std::size_t i = 0; i < names.size() && i < limit; ++i) out += (i ? ", " : "") + names[i];
  if (names.size() > limit) out += ", ... (" + std::to_string(names.size()) + " in all)";
  return out;
}

class ModelBuilder {
 public:
  ModelBuilder(const UrdfXmlDocument& doc, const urdf::ModelInterface& urdf,
               const std::string& source, const fs::path& folder, const UrdfOptions& options)
      : doc_(doc),
        urdf_(urdf),
        source_(source),
        options_(options),
        collisions_(doc, source, folder, options) {}

  UrdfModel build() {
    model_.file = source_;
    model_.robotName = doc_.robotName;
    model_.urdfLinkCount = static_cast<int>(doc_.links.size());
    model_.urdfJointCount = static_cast<int>(doc_.joints.size());
    model_.gravity = options_.gravity;
    model_.gazebo = doc_.gazebo;
    for (std::size_t i = 0; i < doc_.joints.size(); ++i)
      childJoints_[doc_.joints[i].parent].push_back(static_cast<int>(i));
    placeRoot();
    walkTree();
    addInertiasAndCollisions();
    applyTreeInertiaPolicy(model_.bodies, options_, warnings_);
    collectMimics();
    flushWarnings();
    return std::move(model_);
  }

 private:
  void placeRoot() {
    const std::string root = urdf_.getRoot()->name;
    if (root == "world") {
      // By convention the fixed frame, not a body (README pitfall 14); children hang from it.
      model_.frames[root] = {-1, Pose::identity()};
      const auto& inertial = urdf_.getRoot()->inertial;
      if (inertial && inertial->mass > 0.0)
        warnings_.push_back("root link 'world' is the fixed frame: its <inertial> (mass " +
                            std::to_string(inertial->mass) + " kg) is ignored");
      if (options_.base == UrdfBase::Floating)
        warnings_.push_back(
            "floating base ignored: the root link is 'world', the fixed frame by convention");
      enqueueChildren(root);
      return;
    }
    UrdfBody body;
    body.name = root;
    body.parent = -1;
    if (options_.base == UrdfBase::Floating) {
      body.joint = TreeJoint::floating(root + "_floating", options_.basePose);
      model_.floatingBase = true;
    } else {
      body.joint = TreeJoint::fixed(root + "_weld", options_.basePose);
    }
    addBody(std::move(body), root);
    enqueueChildren(root);
  }

  void enqueueChildren(const std::string& link) {
    for (int j : childJoints_[link]) pending_.push(j);
  }

  int addBody(UrdfBody body, const std::string& link) {
    model_.bodies.push_back(std::move(body));
    const int index = static_cast<int>(model_.bodies.size()) - 1;
    model_.frames[link] = {index, Pose::identity()};
    return index;
  }

  /// Bodies in order of their joints' position in the file among the joints whose parent is
  /// placed: parent-first always, and the file's order whenever the file lists parents first.
  void walkTree() {
    while (!pending_.empty()) {
      const int index = pending_.top();
      pending_.pop();
      const UrdfXmlJoint& xml = doc_.joints[static_cast<std::size_t>(index)];
      const urdf::Joint& joint = *urdf_.getJoint(xml.name);
      const UrdfFrame parentFrame = model_.frames.at(xml.parent);
      const Pose parentToJoint = parentFrame.pose * poseOf(joint.parent_to_joint_origin_transform);
      if (joint.type == urdf::Joint::FIXED && options_.fuseFixedJoints && parentFrame.body >= 0) {
        model_.frames[xml.child] = {parentFrame.body, parentToJoint};
        model_.bodies[static_cast<std::size_t>(parentFrame.body)].fusedLinks.push_back(xml.child);
      } else {
        UrdfBody body;
        body.name = xml.child;
        body.parent = parentFrame.body;
        body.joint = treeJoint(joint, xml, parentToJoint, body);
        if (body.joint.nv() > 0) model_.dofNames.push_back(xml.name);
        addBody(std::move(body), xml.child);
      }
      enqueueChildren(xml.child);
    }
  }

  TreeJoint treeJoint(const urdf::Joint& joint, const UrdfXmlJoint& xml, const Pose& parentToJoint,
                      UrdfBody& body) {
    Eigen::Vector3d axis(joint.axis.x, joint.axis.y, joint.axis.z);
    const bool oneDof = joint.type == urdf::Joint::REVOLUTE ||
                        joint.type == urdf::Joint::CONTINUOUS ||
                        joint.type == urdf::Joint::PRISMATIC;
    if (oneDof && std::abs(axis.norm() - 1.0) > 1e-12) {
      std::ostringstream note;
      note << xml.name << " (" << axis.transpose() << ")";
      normalisedAxes_.push_back(note.str());
    }
    if (oneDof) axis.normalize();
    TreeJoint result;
    switch (joint.type) {
      case urdf::Joint::REVOLUTE:
        result = TreeJoint::revolute(xml.name, parentToJoint, axis);
        break;
      case urdf::Joint::CONTINUOUS:
        result = TreeJoint::continuous(xml.name, parentToJoint, axis);
        break;
      case urdf::Joint::PRISMATIC:
        result = TreeJoint::prismatic(xml.name, parentToJoint, axis);
        break;
      case urdf::Joint::FLOATING:
        result = TreeJoint::floating(xml.name, parentToJoint);
        break;
      case urdf::Joint::FIXED:
        result = TreeJoint::fixed(xml.name, parentToJoint);
        break;
      default:
        throw CoulombError(source_ + ":" + std::to_string(xml.line) + ": joint '" + xml.name +
                           "': type '" + xml.type +
                           "' is not supported in reduced coordinates (no planar tree joint). "
                           "Replace it by two prismatic joints and a revolute joint chained "
                           "through massless links");
    }
    if (joint.limits) {
      body.effortLimit = joint.limits->effort;
      body.velocityLimit = joint.limits->velocity;
      const bool limited =
          joint.type == urdf::Joint::REVOLUTE || joint.type == urdf::Joint::PRISMATIC;
      if (limited && joint.limits->lower < joint.limits->upper) {
        result.lower = joint.limits->lower;
        result.upper = joint.limits->upper;
      } else if (limited) {
        placeholderLimits_.push_back(xml.name);
      }
    }
    if (joint.dynamics) {
      if (options_.jointDamping && result.nv() > 0) result.damping = joint.dynamics->damping;
      body.jointFriction = joint.dynamics->friction;
    }
    return result;
  }

  SpatialInertia linkInertia(const std::string& name) {
    const urdf::LinkConstSharedPtr link = urdf_.getLink(name);
    if (!link->inertial) {
      withoutInertial_.push_back(name);
      return {};
    }
    const urdf::Inertial& in = *link->inertial;
    Eigen::Matrix3d inertia;
    inertia << in.ixx, in.ixy, in.ixz, in.ixy, in.iyy, in.iyz, in.ixz, in.iyz, in.izz;
    const Pose origin = poseOf(in.origin);
    const Eigen::Matrix3d r = origin.rotationMatrix();
    if (in.mass == 0.0 && !inertia.isZero(0.0)) massWithoutMassInertia_.push_back(name);
    return {in.mass, origin.position, r * inertia * r.transpose()};  // pitfall 1: R I R^T
  }

  void addInertiasAndCollisions() {
    for (const UrdfXmlLink& link : doc_.links) {
      const UrdfFrame& frame = model_.frames.at(link.name);
      if (frame.body < 0) continue;  // the `world` root
      UrdfBody& body = model_.bodies[static_cast<std::size_t>(frame.body)];
      body.inertia = combine(body.inertia, linkInertia(link.name).transformed(frame.pose));
      const std::size_t kept = urdf_.getLink(link.name)->collision_array.size();
      if (kept < link.collisions.size())
        droppedByUrdfdom_.push_back(link.name + " (" + std::to_string(kept) + " of " +
                                    std::to_string(link.collisions.size()) + " kept)");
      collisions_.addLinkCollisions(link, frame.pose, body);
    }
  }

  void collectMimics() {
    std::vector<std::string> names;
    for (const UrdfXmlJoint& xml : doc_.joints) {
      const urdf::Joint& joint = *urdf_.getJoint(xml.name);
      if (!joint.mimic) continue;
      const urdf::JointConstSharedPtr leader = urdf_.getJoint(joint.mimic->joint_name);
      const bool moving = [](const urdf::JointConstSharedPtr& j) {
        return j && j->type != urdf::Joint::FIXED && j->type != urdf::Joint::FLOATING;
      }(leader);
      if (!moving || joint.type == urdf::Joint::FIXED) {
        warnings_.push_back("joint '" + xml.name + "': <mimic joint=\"" + joint.mimic->joint_name +
                            "\"> ignored (both joints must exist and move)");
        continue;
      }
      model_.mimics.push_back(
          {xml.name, joint.mimic->joint_name, joint.mimic->multiplier, joint.mimic->offset});
      names.push_back(xml.name);
    }
    if (!names.empty())
      warnings_.push_back(std::to_string(names.size()) +
                          " mimic joints are kept as couplings but not enforced yet (each is a "
                          "free DOF, as in DART's forward dynamics): " +
                          joinNames(names));
  }

  void flushWarnings() {
    model_.warnings = doc_.warnings;  // the XML pass's, with their lines, in file order
    auto group = [&](const std::vector<std::string>& names, const std::string& what) {
      if (!names.empty()) model_.warnings.push_back(what + ": " + joinNames(names));
    };
    group(withoutInertial_, "links without <inertial> get zero mass and inertia (URDF default)");
    group(massWithoutMassInertia_,
          "links with mass 0 but a non-zero inertia tensor, kept as given");
    group(placeholderLimits_,
          "joints with <limit lower >= upper> (an exporter's placeholder, e.g. 0 0) read as "
          "unlimited");
    group(normalisedAxes_, "joint axes normalised (written with non-unit length)");
    group(droppedByUrdfdom_,
          "urdfdom dropped <collision> elements after an unknown geometry; read by this loader "
          "instead");
    for (std::string& w : warnings_) model_.warnings.push_back(std::move(w));
    for (std::string& w : collisions_.takeWarnings()) model_.warnings.push_back(std::move(w));
  }

  const UrdfXmlDocument& doc_;
  const urdf::ModelInterface& urdf_;
  std::string source_;
  UrdfOptions options_;
  UrdfCollisionBuilder collisions_;
  UrdfModel model_;
  std::map<std::string, std::vector<int>> childJoints_;
  std::priority_queue<int, std::vector<int>, std::greater<>> pending_;
  std::vector<std::string> warnings_, withoutInertial_, massWithoutMassInertia_, placeholderLimits_,
      normalisedAxes_, droppedByUrdfdom_;
};

}  // namespace

const char* toString(UrdfInertiaStatus status) {
  switch (status) {
    case UrdfInertiaStatus::Physical:
      return "physical";
    case UrdfInertiaStatus::PointMass:
      return "point_mass";
    case UrdfInertiaStatus::Massless:
      return "massless";
    case UrdfInertiaStatus::AsWritten:
      return "as_written_not_physical";
    case UrdfInertiaStatus::Repaired:
      return "repaired";
  }
  return "?";
}

double UrdfModel::totalMass() const {
  double mass = 0.0;
  for (const UrdfBody& body : bodies) mass += body.inertia.mass;
  return mass;
}

UrdfModel parseUrdf(const std::string& text, const std::string& source,
                    const fs::path& baseDirectory, const UrdfOptions& options) {
  const UrdfXmlDocument doc = readUrdfXml(text, source);
  std::vector<std::string> messages;
  const urdf::ModelInterfaceSharedPtr urdf = parseWithUrdfdom(text, messages);
  if (!urdf) {
    std::string reasons;
    for (const std::string& m : messages) reasons += (reasons.empty() ? "" : "; ") + m;
    throw CoulombError(
        source + ": urdfdom refused the file: " + (reasons.empty() ? "no reason given" : reasons) +
        ". Check it with `check_urdf " + source + "`");
  }
  UrdfModel model = ModelBuilder(doc, *urdf, source, baseDirectory, options).build();
  // urdfdom's own complaints, e.g. unknown geometry types, once per text; "... Link [a]" and
  // "... Link [b]" become "... Link [a], [b]".
  std::map<std::string, std::vector<std::string>> names;
  std::map<std::string, int> counts;
  std::vector<std::string> order;
  for (const std::string& m : messages) {
    const std::size_t open = m.find('['), close = m.rfind(']');
    const bool named = open != std::string::npos && close == m.size() - 1 && close > open;
    const std::string key = named ? m.substr(0, open) : m;
    if (counts[key]++ == 0) order.push_back(key);
    if (named) names[key].push_back(m.substr(open, close - open + 1));  // "[name]"
  }
  for (const std::string& key : order)
    model.warnings.push_back(
        "urdfdom: " + key +
        (names.count(key) ? joinNames(names[key])
                          : (counts[key] > 1 ? " (x" + std::to_string(counts[key]) + ")" : "")));
  return model;
}

UrdfModel loadUrdfFile(const fs::path& file, const UrdfOptions& options) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw CoulombError(file.string() + ": cannot open the URDF file (check the path)");
  std::ostringstream text;
  text << in.rdbuf();
  return parseUrdf(text.str(), file.string(), file.parent_path(), options);
}

joints::tree::Articulation toArticulation(const UrdfModel& model) {
  std::vector<joints::tree::TreeLink> links;
  links.reserve(model.bodies.size());
  for (const UrdfBody& body : model.bodies)
    links.push_back({body.name, body.parent, body.joint, body.inertia});
  try {
    return joints::tree::Articulation(std::move(links), model.gravity);
  } catch (const std::exception& e) {
    throw CoulombError(model.file + ": " + e.what());
  }
}

ArticulationDesc toArticulationDesc(const UrdfModel& model, const std::string& name) {
  ArticulationDesc desc;
  desc.name = name;
  for (const UrdfBody& body : model.bodies) {
    ArticulationLinkDesc link;
    link.name = body.name;
    link.parent = body.parent;
    link.joint = body.joint;
    link.inertia = body.inertia;
    if (body.joint.nv() == 1) link.jointFriction = body.jointFriction;  // friction rows
    for (const UrdfCollision& c : body.collisions)
      link.shapes.push_back({c.shape, c.pose, c.material, {}});
    desc.links.push_back(std::move(link));
  }
  return desc;
}

}  // namespace coulomb::engine::io
