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

#include <array>
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

/// Storage of rungeKuttaStep, kept by the caller (no allocation once sized).
struct TreeStepScratch {
  Eigen::VectorXd stageQ, stageQd, combination, errorQ, errorQd;
  std::array<Eigen::VectorXd, 7> stageVelocity, stageAcceleration;  // k of q and of qd per stage
  int substeps = 0;                                                 // of the last call
};

/// Integrates q' = qd, qd' = ABA(q, qd, tau) over h with the embedded Runge-Kutta pair of Dormand
/// and Prince 5(4) (Hairer, Norsett, Wanner, "Solving Ordinary Differential Equations I", sec.
/// II.5, Table 5.2), on the joint manifolds: stage i sits at q (+) h_s sum_j a_ij qd_j from the
/// sub-step's start (body-frame velocities for spherical and floating joints, without the dexp^-1
/// correction of Munthe-Kaas' method). The 4th-order companion estimates the local error; a
/// sub-step is kept when every joint's error is below kTreeStepTolerance (positions [rad or m],
/// velocities relative to 1 + |qd|), else retried shorter; each step starts with one sub-step of
/// h, so a smooth motion costs 6 ABA passes and a whip takes as many sub-steps as its error asks
/// (at most kMaxTreeSubsteps, the last one kept whatever its error). Used between contact events,
/// where no velocity-level row acts on the tree.
inline constexpr double kTreeStepTolerance = 1e-4;
inline constexpr int kMaxTreeSubsteps = 10000;
void rungeKuttaStep(const joints::tree::Articulation& articulation, Eigen::VectorXd& q,
                    Eigen::VectorXd& qd, const Eigen::VectorXd& tau, double h,
                    joints::tree::AbaWorkspace& aba, TreeStepScratch& scratch);

/// One full semi-implicit Euler step without contacts: qd <- v*, then q <- q (+) h qd.
void stepArticulation(const joints::tree::Articulation& articulation, Eigen::VectorXd& q,
                      Eigen::VectorXd& qd, const Eigen::VectorXd& tau, double h,
                      std::span<const geometry::Vector6d> linkWrenches = {});

}  // namespace coulomb::integrators
