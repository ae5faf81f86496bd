#pragma once
// Semi-implicit (symplectic) Euler for articulations in joint coordinates:
//   qd+ = qd + h qdd(q, qd, tau)        (ABA, joints/tree/TreeDynamics.hpp)
//   q+  = q (+) h qd+                   on each joint's manifold
// where (+) is the exponential map of the joint's configuration space: angles and displacements
// add; a spherical joint's quaternion (w, x, y, z) becomes quat * exp(h omega_child) (the velocity
// is in the child frame); a floating joint moves by the SE(3) exponential of its body twist
// (exact for a constant twist over the step); quaternions are re-normalised. World::step splits
// the two halves (predict velocities, contacts, then positions); stepArticulation does both.
#include <coulomb/joints/tree/Articulation.hpp>
#include <coulomb/joints/tree/TreeDynamics.hpp>

#include <span>

namespace coulomb::integrators {

/// q <- q (+) h qd (qd: nv values). Checks sizes and finiteness (std::invalid_argument).
void integrateConfiguration(const joints::tree::Articulation& articulation, Eigen::VectorXd& q,
                            const Eigen::VectorXd& qd, double h);

/// v* = qd + h qdd: the unconstrained velocity of a step (contacts act on it afterwards).
Eigen::VectorXd predictArticulationVelocity(const joints::tree::Articulation& articulation,
                                            const Eigen::VectorXd& q, const Eigen::VectorXd& qd,
                                            const Eigen::VectorXd& tau, double h,
                                            std::span<const geometry::Vector6d> linkWrenches = {});
/// The same in place, qd <- qd + h qdd, with the algorithm's values in `work` and qdd in `qdd`
/// (World::step's form: no allocation once sized).
void predictArticulationVelocity(const joints::tree::Articulation& articulation,
                                 const Eigen::VectorXd& q, Eigen::VectorXd& qd,
                                 const Eigen::VectorXd& tau, double h,
                                 joints::tree::AbaWorkspace& work, Eigen::VectorXd& qdd);

/// One full semi-implicit Euler step without contacts: qd <- v*, then q <- q (+) h qd.
void stepArticulation(const joints::tree::Articulation& articulation, Eigen::VectorXd& q,
                      Eigen::VectorXd& qd, const Eigen::VectorXd& tau, double h,
                      std::span<const geometry::Vector6d> linkWrenches = {});

}  // namespace coulomb::integrators
