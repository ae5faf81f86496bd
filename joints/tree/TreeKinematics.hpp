#pragma once
// Forward kinematics, link velocities, Jacobians and energies of an Articulation
// (Featherstone 2008, sec. 4.2 for the recursive transforms, sec. 4.4 / 8.1 for Jacobians).
//
// Jacobian convention (for constraint rows on links): J maps qd to world-frame velocities,
//   pointJacobian       3 x nv, the world velocity of a world point attached to a link;
//   twistJacobian       6 x nv, rows (velocity of that point; angular velocity), world frame:
//                       the (v, w) ordering of joints/RowBlock.hpp, so a row block written for a
//                       body's COM twist becomes a tree row as  J_row * twistJacobian(com).
// Columns of joints that are not ancestors of the link (or the link's own joint) are zero.
#include <coulomb/joints/tree/Articulation.hpp>
#include <coulomb/joints/tree/PluckerTransform.hpp>

#include <vector>

namespace coulomb::joints::tree {

struct TreeKinematics {
  std::vector<PluckerTransform> parentToLink;  // X_i from the parent link (or world) to link i
  std::vector<geometry::Pose> worldPoses;      // link frames in the world
};

/// Link transforms and world poses at q (checks q; O(n)).
TreeKinematics forwardKinematics(const Articulation& articulation, const Eigen::VectorXd& q);
/// The same into `out`, reusing its storage (no allocation once sized: the step's form).
void forwardKinematics(const Articulation& articulation, const Eigen::VectorXd& q,
                       TreeKinematics& out);

/// Spatial velocity of every link in its own frame, (omega; velocity of the link origin), O(n).
std::vector<geometry::Vector6d> linkVelocities(const Articulation& articulation,
                                               const TreeKinematics& kinematics,
                                               const Eigen::VectorXd& qd);
/// The same into `out`, reusing its storage.
void linkVelocities(const Articulation& articulation, const TreeKinematics& kinematics,
                    const Eigen::VectorXd& qd, std::vector<geometry::Vector6d>& out);

/// World velocity of `worldPoint` moving with link `link`.
Eigen::Vector3d pointVelocity(const Articulation& articulation, const TreeKinematics& kinematics,
                              const Eigen::VectorXd& qd, int link,
                              const Eigen::Vector3d& worldPoint);

Eigen::Matrix<double, 3, Eigen::Dynamic> pointJacobian(const Articulation& articulation,
                                                       const TreeKinematics& kinematics, int link,
                                                       const Eigen::Vector3d& worldPoint);

Eigen::Matrix<double, 6, Eigen::Dynamic> twistJacobian(const Articulation& articulation,
                                                       const TreeKinematics& kinematics, int link,
                                                       const Eigen::Vector3d& worldPoint);
/// The same into `out` (6 x nv), reusing its storage.
void twistJacobian(const Articulation& articulation, const TreeKinematics& kinematics, int link,
                   const Eigen::Vector3d& worldPoint,
                   Eigen::Matrix<double, 6, Eigen::Dynamic>& out);

/// The spatial force in link coordinates (torque about the link origin; force) of a world force
/// applied at a world point on the link: the form the dynamics take as an external wrench.
geometry::Vector6d linkWrenchFromPointForce(const TreeKinematics& kinematics, int link,
                                            const Eigen::Vector3d& worldPoint,
                                            const Eigen::Vector3d& worldForce);

/// 1/2 sum v_i^T I_i v_i + 1/2 sum armature qd^2 (the energy of M(q), CRBA's matrix).
double kineticEnergy(const Articulation& articulation, const TreeKinematics& kinematics,
                     const Eigen::VectorXd& qd);
/// -sum m_i g . c_i with c_i the world COM of link i (zero at the world origin).
double potentialEnergy(const Articulation& articulation, const TreeKinematics& kinematics);
/// Whole-tree linear momentum (world) and angular momentum about the world origin (world).
geometry::Vector6d spatialMomentum(const Articulation& articulation,
                                   const TreeKinematics& kinematics, const Eigen::VectorXd& qd);

}  // namespace coulomb::joints::tree
