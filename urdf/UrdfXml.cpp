#include <coulomb/engine/CoulombError.hpp>
#include <coulomb/urdf/UrdfGazebo.hpp>
#include <coulomb/urdf/UrdfXml.hpp>

#include <tinyxml.h>

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <set>
#include <sstream>

namespace coulomb::engine::io {
namespace {

const char* const kXacroHint =
    " If this is a xacro file, expand it first: `xacro robot.urdf.xacro > robot.urdf`.";

// Throws unless `text` is UTF-8 (RFC 3629 lead and continuation bytes). TinyXML 2.6.2 trusts a
// lead byte's sequence length and reads past the end of the text on a truncated sequence (found by
// fuzz_urdf: heap-buffer-overflow in TiXmlBase::ReadName), so such text never reaches it.
void requireUtf8(const std::string& text, const std::string& source) {
  int line = 1;
  for (std::size_t i = 0; i < text.size();) {
    const auto lead = static_cast<unsigned char>(text[i]);
    std::size_t length = 0;
    if (lead < 0x80)
      length = 1;
    else if (lead >= 0xC2 && lead <= 0xDF)
      length = 2;
    else if (lead >= 0xE0 && lead <= 0xEF)
      length = 3;
    else if (lead >= 0xF0 && lead <= 0xF4)
      length = 4;
    bool valid = length > 0 && i + length <= text.size();
    for (std::size_t k = 1; valid && k < length; ++k)
      valid = (static_cast<unsigned char>(text[i + k]) & 0xC0) == 0x80;
    if (!valid) {
      char hex[8];
      std::snprintf(hex, sizeof hex, "0x%02x", static_cast<unsigned>(lead));
      throw CoulombError(source + ":" + std::to_string(line) + ": not UTF-8 text (byte " + hex +
                         "). Save the file as UTF-8");
    }
    if (lead == '\n') ++line;
    i += length;
  }
}

class XmlChecker {
 public:
  explicit XmlChecker(std::string source) : source_(std::move(source)) {}

  [[noreturn]] void fail(const TiXmlElement* element, const std::string& what,
                         const std::string& problem) const {
    std::ostringstream out;
    out << source_;
    if (element != nullptr) out << ":" << element->Row();
    out << ": " << what << ": " << problem;
    throw CoulombError(out.str());
  }

  std::string requiredAttribute(const TiXmlElement* element, const char* attribute,
                                const std::string& what) const {
    const char* value = element->Attribute(attribute);
    if (value == nullptr || *value == '\0')
      fail(element, what,
           std::string("missing attribute '") + attribute + "'. Add " + attribute + "=\"...\"");
    return value;
  }

  /// `count` whitespace-separated finite numbers (or the fallback when the attribute is absent).
  Eigen::VectorXd numbers(const TiXmlElement* element, const char* attribute, int count,
                          const Eigen::VectorXd& fallback, const std::string& what) const {
    const char* text = element->Attribute(attribute);
    if (text == nullptr) return fallback;
    Eigen::VectorXd values(count);
    const char* cursor = text;
    for (int i = 0; i < count; ++i) {
      char* end = nullptr;
      errno = 0;
      const double value = std::strtod(cursor, &end);
      if (end == cursor || !std::isfinite(value) || errno == ERANGE)
        fail(element, what,
             std::string(attribute) + "=\"" + text + "\" must be " + std::to_string(count) +
                 " finite number" + (count > 1 ? "s" : "") + ". Write e.g. " + attribute + "=\"" +
                 (count == 3 ? "0 0 0" : "1") + "\"");
      values[i] = value;
      cursor = end;
    }
    while (*cursor == ' ' || *cursor == '\t' || *cursor == '\n' || *cursor == '\r') ++cursor;
    if (*cursor != '\0')
      fail(element, what,
           std::string(attribute) + "=\"" + text + "\" has more than " + std::to_string(count) +
               " numbers");
    return values;
  }

  double number(const TiXmlElement* element, const char* attribute, double fallback,
                const std::string& what) const {
    return numbers(element, attribute, 1, Eigen::VectorXd::Constant(1, fallback), what)[0];
  }

  geometry::Pose origin(const TiXmlElement* parent, const std::string& what) const {
    const TiXmlElement* element = parent->FirstChildElement("origin");
    if (element == nullptr) return geometry::Pose::identity();
    const std::string originWhat = what + " <origin>";
    const Eigen::Vector3d xyz = numbers(element, "xyz", 3, Eigen::Vector3d::Zero(), originWhat);
    const Eigen::Vector3d rpy = numbers(element, "rpy", 3, Eigen::Vector3d::Zero(), originWhat);
    return {quaternionFromRpy(rpy), xyz};
  }

  void checkInertial(const TiXmlElement* inertial, const std::string& what) const {
    origin(inertial, what + " <inertial>");
    if (const TiXmlElement* mass = inertial->FirstChildElement("mass")) {
      const double value = number(mass, "value", 0.0, what + " <mass>");
      if (value < 0.0)
        fail(mass, what + " <mass>",
             "mass " + std::to_string(value) + " kg is negative. Use a mass >= 0 (0 = massless)");
    }
    if (const TiXmlElement* inertia = inertial->FirstChildElement("inertia"))
      for (const char* entry : {"ixx", "ixy", "ixz", "iyy", "iyz", "izz"})
        number(inertia, entry, 0.0, what + " <inertia>");
  }

  UrdfXmlGeometry geometry(const TiXmlElement* owner, const std::string& what) const {
    const TiXmlElement* geometryElement = owner->FirstChildElement("geometry");
    if (geometryElement == nullptr || geometryElement->FirstChildElement() == nullptr)
      fail(owner, what, "no <geometry> shape. Add <geometry><box size=\"...\"/></geometry>");
    const TiXmlElement* shape = geometryElement->FirstChildElement();
    UrdfXmlGeometry g;
    g.kind = shape->Value();
    const std::string shapeWhat = what + " <" + g.kind + ">";
    auto positive = [&](double value, const char* attribute) {
      if (!(value > 0.0))
        fail(shape, shapeWhat,
             std::string(attribute) + " must be > 0 (got " + std::to_string(value) + ")");
      return value;
    };
    if (g.kind == "sphere") {
      g.radius = positive(number(shape, "radius", 0.0, shapeWhat), "radius");
    } else if (g.kind == "box") {
      g.size = numbers(shape, "size", 3, Eigen::Vector3d::Zero(), shapeWhat);
      for (int i = 0; i < 3; ++i) positive(g.size[i], "size");
    } else if (g.kind == "cylinder" || g.kind == "capsule") {
      g.radius = positive(number(shape, "radius", 0.0, shapeWhat), "radius");
      g.length = number(shape, "length", 0.0, shapeWhat);
      if (g.kind == "cylinder") positive(g.length, "length");
      if (g.length < 0.0) fail(shape, shapeWhat, "length must be >= 0");
    } else if (g.kind == "mesh") {
      g.filename = requiredAttribute(shape, "filename", shapeWhat);
      g.scale = numbers(shape, "scale", 3, Eigen::Vector3d::Ones(), shapeWhat);
      if ((g.scale.array() == 0.0).any())
        fail(shape, shapeWhat, "scale must have no zero component");
    }  // other kinds: kept as is; the loader reports them as skipped
    return g;
  }

  UrdfXmlLink link(const TiXmlElement* element) const {
    UrdfXmlLink link;
    link.line = element->Row();
    link.name = requiredAttribute(element, "name", "<link>");
    const std::string what = "link '" + link.name + "'";
    if (const TiXmlElement* inertial = element->FirstChildElement("inertial")) {
      link.hasInertial = true;
      checkInertial(inertial, what);
    }
    for (const TiXmlElement* c = element->FirstChildElement("collision"); c != nullptr;
         c = c->NextSiblingElement("collision")) {
      const std::string collisionWhat =
          what + " <collision> #" + std::to_string(link.collisions.size());
      link.collisions.push_back({c->Row(), origin(c, collisionWhat), geometry(c, collisionWhat)});
    }
    if (const TiXmlElement* visual = element->FirstChildElement("visual"))
      if (const TiXmlElement* material = visual->FirstChildElement("material"))
        if (const char* name = material->Attribute("name")) link.visualMaterial = name;
    return link;
  }

  UrdfXmlJoint joint(const TiXmlElement* element) const {
    UrdfXmlJoint joint;
    joint.line = element->Row();
    joint.name = requiredAttribute(element, "name", "<joint>");
    const std::string what = "joint '" + joint.name + "'";
    joint.type = requiredAttribute(element, "type", what);
    static const std::set<std::string> kTypes = {"revolute", "continuous", "prismatic",
                                                 "fixed",    "floating",   "planar"};
    if (kTypes.count(joint.type) == 0)
      fail(element, what,
           "unknown type '" + joint.type +
               "'. Use revolute, continuous, prismatic, fixed, floating or planar");
    for (const char* end : {"parent", "child"}) {
      const TiXmlElement* e = element->FirstChildElement(end);
      if (e == nullptr)
        fail(element, what,
             std::string("no <") + end + "> element. Add <" + end + " link=\"...\"/>");
      (std::strcmp(end, "parent") == 0 ? joint.parent : joint.child) =
          requiredAttribute(e, "link", what + " <" + end + ">");
    }
    origin(element, what);
    if (const TiXmlElement* axis = element->FirstChildElement("axis")) {
      const Eigen::Vector3d a = numbers(axis, "xyz", 3, Eigen::Vector3d::UnitX(), what + " <axis>");
      if (a.norm() < 1e-12 && joint.type != "fixed" && joint.type != "floating")
        fail(axis, what + " <axis>", "the axis is zero. Give a direction, e.g. xyz=\"0 0 1\"");
    }
    if (const TiXmlElement* limit = element->FirstChildElement("limit"))
      for (const char* entry : {"lower", "upper", "effort", "velocity"})
        number(limit, entry, 0.0, what + " <limit>");
    if (const TiXmlElement* dynamics = element->FirstChildElement("dynamics"))
      for (const char* entry : {"damping", "friction"}) {
        const double value = number(dynamics, entry, 0.0, what + " <dynamics>");
        if (value < 0.0) fail(dynamics, what + " <dynamics>", std::string(entry) + " must be >= 0");
      }
    if (const TiXmlElement* mimic = element->FirstChildElement("mimic")) {
      requiredAttribute(mimic, "joint", what + " <mimic>");
      number(mimic, "multiplier", 1.0, what + " <mimic>");
      number(mimic, "offset", 0.0, what + " <mimic>");
    }
    return joint;
  }

  void checkTree(const UrdfXmlDocument& doc, const TiXmlElement* robot) const {
    std::map<std::string, int> linkLine;
    for (const UrdfXmlLink& link : doc.links)
      if (!linkLine.emplace(link.name, link.line).second)
        fail(nullptr, "link '" + link.name + "'",
             "declared twice (lines " + std::to_string(linkLine[link.name]) + " and " +
                 std::to_string(link.line) + "). Rename or remove one");
    std::map<std::string, const UrdfXmlJoint*> parentJoint, jointNames;
    for (const UrdfXmlJoint& joint : doc.joints) {
      const std::string what = "joint '" + joint.name + "'";
      if (!jointNames.emplace(joint.name, &joint).second)
        throw CoulombError(source_ + ":" + std::to_string(joint.line) + ": " + what +
                           ": declared twice. Rename or remove one");
      for (const std::string* end : {&joint.parent, &joint.child}) {
        if (linkLine.count(*end) != 0) continue;
        std::string problem = std::string(end == &joint.parent ? "parent" : "child") + " link '" +
                              *end + "' is not declared";
        if (*end == "world")
          problem +=
              ". 'world' is the fixed frame by convention (Drake, Gazebo), but urdfdom and "
              "this loader require it declared: add <link name=\"world\"/> inside <robot>, or "
              "remove this joint to load the robot with its root welded at the origin";
        else
          problem += ". Add <link name=\"" + *end + "\"/> or correct the name";
        throw CoulombError(source_ + ":" + std::to_string(joint.line) + ": " + what + ": " +
                           problem);
      }
      if (joint.parent == joint.child)
        throw CoulombError(source_ + ":" + std::to_string(joint.line) + ": " + what +
                           ": joins link '" + joint.child + "' to itself (a cycle)");
      if (const auto [it, inserted] = parentJoint.emplace(joint.child, &joint); !inserted)
        throw CoulombError(source_ + ":" + std::to_string(joint.line) + ": " + what + ": link '" +
                           joint.child + "' already has parent joint '" + it->second->name +
                           "' (line " + std::to_string(it->second->line) +
                           "). A URDF is a tree: each link has at most one parent joint; close "
                           "loops with constraints instead");
    }
    std::vector<std::string> roots;
    for (const UrdfXmlLink& link : doc.links)
      if (parentJoint.count(link.name) == 0) roots.push_back(link.name);
    if (roots.size() > 1) {
      std::string names;
      for (const std::string& r : roots) names += (names.empty() ? "'" : ", '") + r + "'";
      fail(robot, "<robot>",
           "several root links (" + names +
               "): every link but one needs a parent joint. Join them with fixed or moving "
               "joints into one tree");
    }
    // Walk up from every link: a walk longer than the link count is a cycle.
    for (const UrdfXmlLink& link : doc.links) {
      std::string current = link.name;
      for (std::size_t steps = 0; parentJoint.count(current) != 0; ++steps) {
        const UrdfXmlJoint* j = parentJoint[current];
        if (steps > doc.links.size())
          throw CoulombError(source_ + ":" + std::to_string(j->line) + ": joint '" + j->name +
                             "': closes a cycle through link '" + link.name +
                             "'. A URDF is a tree: remove one joint of the loop");
        current = j->parent;
      }
    }
  }

 private:
  std::string source_;
};

}  // namespace

Eigen::Quaterniond quaternionFromRpy(const Eigen::Vector3d& rpy) {
  return (Eigen::AngleAxisd(rpy.z(), Eigen::Vector3d::UnitZ()) *
          Eigen::AngleAxisd(rpy.y(), Eigen::Vector3d::UnitY()) *
          Eigen::AngleAxisd(rpy.x(), Eigen::Vector3d::UnitX()))
      .normalized();
}

UrdfXmlDocument readUrdfXml(const std::string& text, const std::string& source) {
  XmlChecker check(source);
  requireUtf8(text, source);
  TiXmlDocument document;
  document.Parse(text.c_str());
  if (document.Error())
    throw CoulombError(source + ":" + std::to_string(document.ErrorRow()) + ":" +
                       std::to_string(document.ErrorCol()) + ": not well-formed XML (" +
                       document.ErrorDesc() + "). Fix the markup near that line");
  const TiXmlElement* robot = document.RootElement();
  if (robot == nullptr) throw CoulombError(source + ": empty document: no <robot> element");
  if (std::string(robot->Value()) != "robot")
    check.fail(robot, "<" + std::string(robot->Value()) + ">",
               "the root element must be <robot>." + std::string(kXacroHint));
  UrdfXmlDocument doc;
  if (const char* name = robot->Attribute("name")) doc.robotName = name;
  bool xacro = robot->Attribute("xmlns:xacro") != nullptr;
  UrdfGazeboReader gazebo(source);
  for (const TiXmlElement* e = robot->FirstChildElement(); e != nullptr;
       e = e->NextSiblingElement()) {
    const std::string tag = e->Value();
    if (tag == "link") {
      doc.links.push_back(check.link(e));
    } else if (tag == "joint") {
      doc.joints.push_back(check.joint(e));
    } else if (tag == "gazebo") {
      gazebo.add(*e);
    } else if (tag.rfind("xacro:", 0) == 0) {
      xacro = true;
    }
  }
  if (doc.links.empty())
    check.fail(robot, "<robot>",
               std::string("no <link> elements found.") + (xacro ? kXacroHint : ""));
  check.checkTree(doc, robot);
  std::set<std::string> links, joints;
  for (const UrdfXmlLink& link : doc.links) links.insert(link.name);
  for (const UrdfXmlJoint& joint : doc.joints) joints.insert(joint.name);
  doc.gazebo = gazebo.finish(links, joints, doc.warnings);
  return doc;
}

}  // namespace coulomb::engine::io
