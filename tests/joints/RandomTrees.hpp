#pragma once
// Random articulations for the tree tests: mixed joint types, random placements, axes, inertias
// (valid by construction), damping and armature; fixed or floating base. Deterministic per seed.
#include <coulomb/joints/tree/Articulation.hpp>

#include <Eigen/Geometry>

#include <random>
#include <string>
#include <vector>

namespace coulomb::joints::tree::randomtree {

class RandomSource {
 public:
  explicit RandomSource(unsigned seed) : engine_(seed) {}
  double uniform(double lo, double hi) {
    return std::uniform_real_distribution<double>(lo, hi)(engine_);
  }
  int integer(int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(engine_); }
  Eigen::Vector3d vector(double scale) {
    return Eigen::Vector3d(uniform(-scale, scale), uniform(-scale, scale), uniform(-scale, scale));
  }
  Eigen::Vector3d unitVector() {
    Eigen::Vector3d v;
    do v = vector(1.0);
    while (v.norm() < 0.1);
    return v.normalized();
  }
  Eigen::Quaterniond rotation() {
    return Eigen::Quaterniond(uniform(-1, 1), uniform(-1, 1), uniform(-1, 1), uniform(-1, 1))
        .normalized();
  }
  geometry::Pose pose(double scale) { return {rotation(), vector(scale)}; }
  geometry::SpatialInertia inertia() {
    geometry::SpatialInertia inertia;
    inertia.mass = uniform(0.5, 2.0);
    inertia.centerOfMass = vector(0.3);
    // Principal moments of a box with random sides: the triangle inequality holds.
    const Eigen::Vector3d sides(uniform(0.1, 0.6), uniform(0.1, 0.6), uniform(0.1, 0.6));
    const Eigen::Vector3d s2 = sides.cwiseProduct(sides);
    const Eigen::Vector3d moments =
        inertia.mass / 12.0 * Eigen::Vector3d(s2.y() + s2.z(), s2.x() + s2.z(), s2.x() + s2.y());
    const Eigen::Matrix3d r = rotation().toRotationMatrix();
    inertia.inertiaAboutCom = r * moments.asDiagonal() * r.transpose();
    return inertia;
  }
  std::mt19937& engine() { return engine_; }

 private:
  std::mt19937 engine_;
};

struct RandomTreeOptions {
  int links = 8;
  bool floatingBase = false;
  bool withDampingAndArmature = true;
};

inline Articulation randomTree(RandomSource& random, const RandomTreeOptions& options) {
  std::vector<TreeLink> links;
  for (int i = 0; i < options.links; ++i) {
    TreeLink link;
    link.name = "link" + std::to_string(i);
    link.parent = i == 0 ? -1 : random.integer(std::max(-1, i - 4), i - 1);
    if (i > 0 && options.floatingBase && link.parent < 0) link.parent = 0;
    const std::string jointName = "joint" + std::to_string(i);
    const geometry::Pose placement = random.pose(0.5);
    if (i == 0 && options.floatingBase) {
      link.joint = TreeJoint::floating(jointName, placement);
    } else {
      switch (random.integer(0, 5)) {
        case 0:
          link.joint = TreeJoint::revolute(jointName, placement, random.unitVector());
          break;
        case 1:
          link.joint = TreeJoint::continuous(jointName, placement, random.unitVector());
          break;
        case 2:
          link.joint = TreeJoint::prismatic(jointName, placement, random.unitVector());
          break;
        case 3:
          link.joint = TreeJoint::spherical(jointName, placement);
          break;
        case 4:
          link.joint = TreeJoint::fixed(jointName, placement);
          break;
        default:
          link.joint = TreeJoint::revolute(jointName, placement, random.unitVector());
          break;
      }
    }
    if (options.withDampingAndArmature && link.joint.nv() > 0) {
      link.joint.damping = random.uniform(0.0, 0.5);
      link.joint.armature = random.uniform(0.0, 0.1);
    }
    link.inertia = random.inertia();
    links.push_back(link);
  }
  return Articulation(links);
}

/// A valid random configuration: angles, displacements and unit quaternions.
inline Eigen::VectorXd randomConfiguration(const Articulation& articulation, RandomSource& random) {
  Eigen::VectorXd q(articulation.nq());
  for (int i = 0; i < articulation.linkCount(); ++i) {
    const TreeJoint& joint = articulation.link(i).joint;
    const int start = articulation.qIndex(i);
    switch (joint.type) {
      case TreeJointType::Spherical:
      case TreeJointType::Floating: {
        const int offset = joint.type == TreeJointType::Floating ? 3 : 0;
        if (offset == 3) q.segment<3>(start) = random.vector(1.0);
        const Eigen::Quaterniond r = random.rotation();
        q.segment<4>(start + offset) << r.w(), r.x(), r.y(), r.z();
        break;
      }
      case TreeJointType::Fixed:
        break;
      default:
        q(start) = random.uniform(-3.0, 3.0);
        break;
    }
  }
  return q;
}

inline Eigen::VectorXd randomVector(int size, RandomSource& random, double scale) {
  Eigen::VectorXd v(size);
  for (int i = 0; i < size; ++i) v(i) = random.uniform(-scale, scale);
  return v;
}

}  // namespace coulomb::joints::tree::randomtree
