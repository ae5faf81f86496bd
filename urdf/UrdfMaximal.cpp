// URDF robots as free bodies and maximal-coordinate joints (UrdfMaximal.hpp, docs/urdf.md).
#include <coulomb/joints/tree/TreeKinematics.hpp>
#include <coulomb/urdf/UrdfInertia.hpp>
#include <coulomb/urdf/UrdfMaximal.hpp>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace coulomb::engine::io {
namespace {

using joints::tree::TreeJointType;

/// A deterministic unit vector perpendicular to `axis` (the joint frames' normal).
Eigen::Vector3d anyPerpendicular(const Eigen::Vector3d& axis) {
  Eigen::Index least = 0;
  axis.cwiseAbs().minCoeff(&least);
  return axis.cross(Eigen::Vector3d::Unit(least)).normalized();
}

/// The body's inertia, lifted to what a free body needs (UrdfMaximalOptions), with a warning.
geometry::SpatialInertia freeBodyInertia(const UrdfBody& body, const UrdfMaximalOptions& options,
                                         std::vector<std::string>& warnings) {
  geometry::SpatialInertia inertia = body.inertia;
  std::ostringstream lifted;
  if (!(inertia.mass >= options.minimumMass)) {
    lifted << " mass " << inertia.mass << " -> " << options.minimumMass << " kg";
    inertia.mass = options.minimumMass;
  }
  const Eigen::Matrix3d symmetric =
      0.5 * (inertia.inertiaAboutCom + inertia.inertiaAboutCom.transpose());
  const double smallest =
      Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(symmetric).eigenvalues()[0];
  if (smallest < options.minimumInertia) {
    inertia.inertiaAboutCom =
        symmetric + (options.minimumInertia - smallest) * Eigen::Matrix3d::Identity();
    lifted << " smallest principal moment " << smallest << " -> " << options.minimumInertia
           << " kg m^2";
  }
  // The tree keeps tensors that break the triangle inequality (UrdfInertia.hpp); a free body
  // must be one a real mass distribution has (World::createBody checks it).
  const Eigen::Matrix3d physical = withTriangleInequality(inertia.inertiaAboutCom);
  if (physical != inertia.inertiaAboutCom) {
    lifted << " principal moments "
           << geometry::principalAxes(inertia.inertiaAboutCom).moments.transpose() << " -> "
           << geometry::principalAxes(physical).moments.transpose()
           << " kg m^2 (triangle inequality)";
    inertia.inertiaAboutCom = physical;
  }
  if (!lifted.str().empty())
    warnings.push_back("body '" + body.name + "': a free body needs mass and inertia:" +
                       lifted.str() + " (maximal coordinates only)");
  return inertia;
}

/// Hinge or prismatic frames: A = the joint frame in the parent body (or the world), B = the
/// child body frame, which is the joint frame at q = 0 (TreeJoint.hpp); the normals are the same
/// joint-frame vector, so the joint's coordinate equals the tree's q.
void setFrames(const joints::tree::TreeJoint& joint, joints::JointDef& def) {
  const Eigen::Vector3d normal = anyPerpendicular(joint.axis);
  def.frameA.anchor = joint.parentToJoint.position;
  def.frameA.axis = joint.parentToJoint.rotation * joint.axis;
  def.frameA.normal = joint.parentToJoint.rotation * normal;
  def.frameB.anchor = Eigen::Vector3d::Zero();
  def.frameB.axis = joint.axis;
  def.frameB.normal = normal;
}

}  // namespace

UrdfMaximal toMaximal(const UrdfModel& model, const std::string& name,
                      const std::optional<Eigen::VectorXd>& q, const UrdfMaximalOptions& options) {
  const joints::tree::Articulation tree = toArticulation(model);
  const Eigen::VectorXd configuration = q.value_or(tree.neutralConfiguration());
  try {
    tree.checkConfiguration(configuration);
  } catch (const std::invalid_argument& e) {
    throw CoulombError(model.file + ": robot '" + name + "': " + e.what());
  }
  const joints::tree::TreeKinematics kin = joints::tree::forwardKinematics(tree, configuration);
  UrdfMaximal out;
  std::vector<std::string> undamped;
  for (std::size_t i = 0; i < model.bodies.size(); ++i) {
    const UrdfBody& body = model.bodies[i];
    const joints::tree::TreeJoint& joint = body.joint;
    BodyDesc desc;
    desc.name = name + "/" + body.name;
    desc.pose = kin.worldPoses[i];
    for (const UrdfCollision& c : body.collisions) {
      ShapeDesc shape{c.shape, c.pose, c.material, {}};
      shape.filter.category = options.linkCategory;
      shape.filter.mask = ~options.linkCategory;
      desc.shapes.push_back(std::move(shape));
    }
    const bool welded = body.parent < 0 && joint.type == TreeJointType::Fixed;
    if (welded)
      desc.motionType = geometry::MotionType::Static;  // a fixed base: the root does not move
    else
      desc.mass = freeBodyInertia(body, options, out.warnings);
    out.bodies.push_back(std::move(desc));
    if (welded || joint.type == TreeJointType::Floating) continue;  // no joint

    UrdfMaximalJoint j;
    j.bodyA = body.parent;
    j.bodyB = static_cast<int>(i);
    j.def.name = joint.name;
    switch (joint.type) {
      case TreeJointType::Revolute:
      case TreeJointType::Continuous:
        j.def.type = joints::JointType::Hinge;
        break;
      case TreeJointType::Prismatic:
        j.def.type = joints::JointType::Prismatic;
        break;
      case TreeJointType::Fixed:
        j.def.type = joints::JointType::Fixed;
        break;
      default:
        throw CoulombError(model.file + ": joint '" + joint.name +
                           "' has no maximal-coordinate form; load the robot as a tree");
    }
    setFrames(joint, j.def);
    if (j.def.type != joints::JointType::Fixed) {
      if (std::isfinite(joint.lower) && std::isfinite(joint.upper) && joint.lower < joint.upper)
        j.def.limit = {true, joint.lower, joint.upper, 0.0};
      j.def.friction = body.jointFriction;
      if (joint.damping > 0.0) undamped.push_back(joint.name);
      out.jointIndex[joint.name] = static_cast<int>(out.joints.size());
    }
    out.joints.push_back(std::move(j));
  }
  if (!undamped.empty()) {
    std::string list;
    for (const std::string& n : undamped) list += (list.empty() ? "" : ", ") + n;
    out.warnings.push_back("joint damping is not carried in maximal coordinates (joints: " + list +
                           ")");
  }
  return out;
}

UrdfMaximalIds createMaximal(World& world, const UrdfMaximal& robot) {
  UrdfMaximalIds ids;
  for (const BodyDesc& body : robot.bodies) ids.bodies.push_back(world.createBody(body));
  for (const UrdfMaximalJoint& joint : robot.joints) {
    joints::JointDef def = joint.def;
    if (joint.bodyA >= 0) def.bodyA = ids.bodies[static_cast<std::size_t>(joint.bodyA)];
    if (joint.bodyB >= 0) def.bodyB = ids.bodies[static_cast<std::size_t>(joint.bodyB)];
    ids.joints.push_back(world.createJoint(def));
  }
  return ids;
}

}  // namespace coulomb::engine::io
