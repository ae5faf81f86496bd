#pragma once
// A kinematic tree of rigid links in reduced coordinates (Featherstone 2008, chapter 4.1-4.2:
// regular numbering, parent array lambda(i) < i). The model is immutable after construction and
// validated there; the algorithms (TreeKinematics, TreeDynamics, ArticulationImpulse) are free
// functions over it, so one model can serve several threads.
//
// Conventions
//  - Links are in topological order: link i's parent index is -1 (the world) or < i.
//  - q stacks each link's joint coordinates in link order (TreeJoint.hpp gives the layout per
//    type; quaternions are (w, x, y, z)); qd (size nv) likewise, so q and qd of a link start at
//    qIndex(i) and vIndex(i). Floating: q = (p, quat), qd = (omega_body, v_body).
//  - Spatial vectors follow geometry/Spatial.hpp: angular first, in link coordinates (the link
//    frame is the child frame of its joint); forces are (torque about the link origin, force).
//  - Gravity is a world vector, default (0, 0, -9.81) m/s^2 (z up).
#include <coulomb/geometry/SpatialInertia.hpp>
#include <coulomb/joints/tree/TreeJoint.hpp>

#include <string>
#include <vector>

namespace coulomb::joints::tree {

struct TreeLink {
  std::string name;
  int parent = -1;                   // index of the parent link, -1 for the world
  TreeJoint joint;                   // joint between the parent and this link
  geometry::SpatialInertia inertia;  // in the link frame; mass 0 allowed (massless frames)
};

class Articulation {
 public:
  /// Validates every link and joint; throws std::invalid_argument naming the link (and joint) on
  /// a parent index not before the link, a bad joint (TreeJoint::validate), a non-finite inertia,
  /// a negative mass or a tensor that is not symmetric positive semidefinite (all a tree needs:
  /// the triangle inequality is not required, docs/articulations.md), or non-finite gravity.
  explicit Articulation(std::vector<TreeLink> links,
                        const Eigen::Vector3d& gravity = Eigen::Vector3d(0.0, 0.0, -9.81));

  [[nodiscard]] int linkCount() const { return static_cast<int>(links_.size()); }
  [[nodiscard]] int nq() const { return nq_; }
  [[nodiscard]] int nv() const { return nv_; }
  [[nodiscard]] const TreeLink& link(int i) const { return links_[static_cast<size_t>(i)]; }
  [[nodiscard]] const std::vector<TreeLink>& links() const { return links_; }
  [[nodiscard]] int parent(int i) const { return link(i).parent; }
  [[nodiscard]] int qIndex(int i) const { return qIndex_[static_cast<size_t>(i)]; }
  [[nodiscard]] int vIndex(int i) const { return vIndex_[static_cast<size_t>(i)]; }
  /// -1 when no link has that name.
  [[nodiscard]] int findLink(const std::string& name) const;
  [[nodiscard]] const Eigen::Vector3d& gravity() const { return gravity_; }
  /// True when some root link has a floating joint.
  [[nodiscard]] bool hasFloatingBase() const;

  /// 6 x 6 spatial inertia of link i about its origin (Featherstone eq. 2.63), cached.
  [[nodiscard]] const geometry::Matrix6d& spatialInertia(int i) const {
    return spatialInertia_[static_cast<size_t>(i)];
  }
  /// Motion subspace of link i's joint (child frame), cached.
  [[nodiscard]] const MotionSubspace& motionSubspace(int i) const {
    return subspace_[static_cast<size_t>(i)];
  }

  /// Every joint at its neutral configuration (identity quaternions).
  [[nodiscard]] Eigen::VectorXd neutralConfiguration() const;

  /// Throw std::invalid_argument (naming the first bad entry: link, joint, coordinate) when a
  /// vector has the wrong size or a non-finite value, or a quaternion has (near) zero norm.
  void checkConfiguration(const Eigen::VectorXd& q) const;
  void checkVelocity(const Eigen::VectorXd& qd, const char* what = "qd") const;

 private:
  std::vector<TreeLink> links_;
  Eigen::Vector3d gravity_;
  std::vector<int> qIndex_, vIndex_;
  std::vector<geometry::Matrix6d> spatialInertia_;
  std::vector<MotionSubspace> subspace_;
  int nq_ = 0, nv_ = 0;
};

}  // namespace coulomb::joints::tree
