#pragma once
// Geometric stiffness of joint forces on a rigid body's rotation, and the inertia that keeps its
// explicit treatment stable.
//
// A velocity-level step (and its predicted-state correction, which is SHAKE) applies the joint
// impulses along the rows J(x_n) of the start of the step: the change of their direction as the
// body turns, the geometric stiffness K = d(J^T lambda)/dx, is integrated explicitly. A force f at
// the arm r from the centre of mass (r turns with the body, f does not) gives the torque r x f and
//     d(r x f) = (dtheta x r) x f = [f]x [r]x dtheta,   K = [f]x [r]x = r f^T - (f . r) I
// (Andrews, Teichmann, Kry, "Geometric Stiffness for Real-time Constrained Multibody Dynamics",
// CGF 36(2) 2017, sec. 3). A link hanging under tension T has k = T L about its transverse axes;
// its zig-zag mode (links turning about their centres, alternately) has omega^2 = k / I and, like
// any explicit step, is stable only for omega h < 2. Ten 0.1 kg links under a 10 kg load at
// h = 0.01: T L = 9.8 N m, I = 7.6e-5 kg m^2, omega h = 3.6, growth x10.9 per step.
//
// The remedy of Andrews et al. is to solve with M + h^2 |K| in place of M (an implicit geometric
// stiffness, diagonal approximation), which damps. Here it is applied only along the directions
// where the explicit step is unstable, and only by as much as needed: for every eigenpair
// (k_j, v_j) of sym(K), with I_j = v_j^T I v_j, where h^2 |k_j| > 4 I_j (omega_j h > 2) the
// inertia gains (h^2 |k_j| / 2 - I_j) v_j v_j^T (omega_j h = sqrt 2). Bodies whose joint forces
// keep the explicit step stable are untouched.
#include <Eigen/Core>

namespace coulomb::joints {

/// K = [f]x [r]x [N m / rad]: the change of the torque of `force` [N] at `arm` [m] (world axes,
/// from the centre of mass) per rotation of the body (world axes).
Eigen::Matrix3d rotationalGeometricStiffness(const Eigen::Vector3d& force,
                                             const Eigen::Vector3d& arm);

/// The world inertia [kg m^2] to solve the joint rows with: `inertia` (symmetric positive
/// definite, world axes), raised to h^2 |k_j| / 2 along each eigen-direction of sym(stiffness)
/// where h^2 |k_j| > 4 I_j (omega_j h > 2); `inertia` itself where no direction needs it.
Eigen::Matrix3d stabilizingInertia(const Eigen::Matrix3d& inertia, const Eigen::Matrix3d& stiffness,
                                   double h);

}  // namespace coulomb::joints
