#pragma once
// Internal to the URDF loader (urdf/Urdf*.cpp): a first pass over the URDF's XML with
// TinyXML (the parser urdfdom 3 itself uses) that checks what urdfdom would refuse or accept
// silently, with line numbers and a fix in every message, and collects what urdfdom loses:
// document order of links and joints, every <collision> (including Bullet's <capsule>, which
// urdfdom drops), visual material names and the <gazebo> extensions (UrdfGazebo.hpp).
#include <coulomb/geometry/Pose.hpp>
#include <coulomb/urdf/UrdfLoader.hpp>

#include <Eigen/Core>

#include <optional>
#include <string>
#include <vector>

namespace coulomb::engine::io {

struct UrdfXmlGeometry {
  std::string kind;                                // "sphere", "box", "cylinder", "capsule", "mesh"
  Eigen::Vector3d size = Eigen::Vector3d::Zero();  // box edge lengths
  double radius = 0.0;
  double length = 0.0;   // cylinder: full length; capsule: distance between the cap centres
  std::string filename;  // mesh
  Eigen::Vector3d scale = Eigen::Vector3d::Ones();
};

struct UrdfXmlCollision {
  int line = 0;
  geometry::Pose origin;  // in the link frame
  UrdfXmlGeometry geometry;
};

struct UrdfXmlLink {
  std::string name;
  int line = 0;
  bool hasInertial = false;
  std::vector<UrdfXmlCollision> collisions;
  std::string visualMaterial;  // name of the first visual's <material>, "" if none
};

struct UrdfXmlJoint {
  std::string name, type, parent, child;
  int line = 0;
};

struct UrdfXmlDocument {
  std::string robotName;
  std::vector<UrdfXmlLink> links;     // document order
  std::vector<UrdfXmlJoint> joints;   // document order
  UrdfGazeboUse gazebo;               // <gazebo> extensions
  std::vector<std::string> warnings;  // "<file>:<line>: ..." for values dropped, in file order
};

/// Throws CoulombError "<source>:<line>: <element>: <problem>. <fix>" for malformed XML, a root
/// that is not <robot> (xacro hint), no links, missing or duplicate names, unknown joint types,
/// joints naming undeclared links (the undeclared `world` of Drake files), a link with two parent
/// joints, a cycle, several roots, non-finite or malformed numbers, negative mass, and invalid
/// geometry sizes. <gazebo> extensions never throw (UrdfGazebo.hpp): their problems are warnings.
UrdfXmlDocument readUrdfXml(const std::string& text, const std::string& source);

/// R = Rz(yaw) Ry(pitch) Rx(roll), URDF's fixed-axis roll-pitch-yaw.
Eigen::Quaterniond quaternionFromRpy(const Eigen::Vector3d& rpy);

}  // namespace coulomb::engine::io
