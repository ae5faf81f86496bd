#include <coulomb/geometry/Quaternion.hpp>
#include <coulomb/integrators/FreeRotation.hpp>

#include <cmath>

namespace coulomb::integrators {

Eigen::Quaterniond rotateTorqueFree(const Eigen::Quaterniond& orientation,
                                    const Eigen::Quaterniond& principalFrame,
                                    const Eigen::Vector3d& principalMoments,
                                    const Eigen::Vector3d& angularMomentum, double h) {
  const Eigen::Quaterniond toPrincipal = orientation * principalFrame;
  return (rotatePrincipalFrame(toPrincipal, toPrincipal.conjugate() * angularMomentum,
                               principalMoments, h) *
          principalFrame.conjugate())
      .normalized();
}

namespace {

// The free symmetric top (moments I_e, I_e, I_u about principal axes, the unique one `axis`):
// Q(t) = exp(t L / I_e) Q(0) exp(t pi_u (1/I_u - 1/I_e) e_u), L = Q pi (Landau and Lifshitz,
// Mechanics, sec. 33, the regular precession). With exp(t L / I_e) Q = Q exp(t pi / I_e) both
// factors act on the right: two rotations, exact at any step, no sub-stepping. A sphere (three
// equal moments) is the case pi_u (1/I_u - 1/I_e) = 0.
Eigen::Quaterniond rotateSymmetricTop(const Eigen::Quaterniond& toPrincipal,
                                      const Eigen::Vector3d& bodyMomentum,
                                      const Eigen::Vector3d& principalMoments, int axis, double h) {
  const double equal = principalMoments[(axis + 1) % 3], own = principalMoments[axis];
  const Eigen::Quaterniond precession = geometry::quaternionExp((h / equal) * bodyMomentum);
  const double spin = h * bodyMomentum[axis] * (1.0 / own - 1.0 / equal);
  if (spin == 0.0) return toPrincipal * precession;
  return toPrincipal * precession * geometry::axisRotation(axis, spin);
}

}  // namespace

Eigen::Quaterniond rotatePrincipalFrame(const Eigen::Quaterniond& toPrincipal,
                                        const Eigen::Vector3d& bodyMomentum,
                                        const Eigen::Vector3d& principalMoments, double h) {
  // Two equal moments (capsules, cylinders, cubes, spheres): the exact flow, at any step.
  const Eigen::Vector3d& m = principalMoments;
  const int unique = m[0] == m[1] ? 2 : m[0] == m[2] ? 1 : m[1] == m[2] ? 0 : -1;
  if (unique >= 0) return rotateSymmetricTop(toPrincipal, bodyMomentum, m, unique, h);
  // Q: principal axes -> world. The body momentum pi = Q^T L; the flow of T_k = pi_k^2/(2 I_k)
  // is Q <- Q R_k(t pi_k / I_k), pi <- R_k^T pi (DLM 1997, eqs. 3.5-3.7), so L = Q pi is unchanged.
  // R_k is a rotation about a coordinate axis: Q R_k and R_k^T pi are written out (half the
  // arithmetic of general quaternion products; one sine and cosine per sub-rotation).
  Eigen::Vector4d q(toPrincipal.w(), toPrincipal.x(), toPrincipal.y(), toPrincipal.z());
  Eigen::Vector3d pi = bodyMomentum;
  const auto subRotation = [&](int axis, double step) {
    const double half = 0.5 * step * pi[axis] / principalMoments[axis];
    const double c = std::cos(half), s = std::sin(half);
    // Q R_k with R_k = (c, s e_k): w = c w - s v_k; v = c v + s w e_k + s (v x e_k).
    const int i = (axis + 1) % 3, j = (axis + 2) % 3;
    const double w = q[0], vk = q[1 + axis], vi = q[1 + i], vj = q[1 + j];
    q[0] = c * w - s * vk;
    q[1 + axis] = c * vk + s * w;
    q[1 + i] = c * vi + s * vj;  // (v x e_k)_i = v_j, (v x e_k)_j = -v_i
    q[1 + j] = c * vj - s * vi;
    // R_k^T pi: the plane (i, j) turned by -angle, cos angle = c^2 - s^2, sin angle = 2 s c.
    const double cosAngle = c * c - s * s, sinAngle = 2.0 * s * c;
    const double pii = pi[i], pij = pi[j];
    pi[i] = cosAngle * pii + sinAngle * pij;
    pi[j] = cosAngle * pij - sinAngle * pii;
  };
  // The splitting's error grows with the angle an axis turns per step. At a few radians per step
  // (a thin plank at 200 rad/s, dt = 1/60: 3.3 rad) it moves body momentum onto the axis of the
  // smallest moment and the energy grows without bound (x370 in three steps, measured), although
  // |pi| and L stay exact. So a step turns each axis by at most kMaxTurn: a fast spinner takes
  // as many sub-steps as it needs, and a body slower than kMaxTurn / h
  // takes the single step it always took (60 rad/s at dt = 1/60).
  constexpr double kMaxTurn = 1.0;  // [rad] per axis and sub-step: the bound that keeps a 1 m plank
                                    // at 200 rad/s within 5 % of its energy over 10 s
  constexpr int kMaxSubSteps = 1024;
  double remaining = h;
  for (int count = 0; remaining > 0 && count < kMaxSubSteps; ++count) {
    const double rate = pi.cwiseQuotient(principalMoments).cwiseAbs().maxCoeff();
    const double dt =
        !(rate * remaining > kMaxTurn) || count + 1 == kMaxSubSteps ? remaining : kMaxTurn / rate;
    subRotation(0, 0.5 * dt);
    subRotation(1, 0.5 * dt);
    subRotation(2, dt);
    subRotation(1, 0.5 * dt);
    subRotation(0, 0.5 * dt);
    remaining = dt == remaining ? 0.0 : remaining - dt;
  }
  return {q[0], q[1], q[2], q[3]};
}

Eigen::Quaterniond torqueFreeOrientation(const geometry::BodyState& state, std::size_t i, double h,
                                         Eigen::Vector3d* momentum) {
  const Eigen::Quaterniond toPrincipal = state.poses[i].rotation * state.principalFrames[i];
  const Eigen::Vector3d bodyMomentum =
      state.principalMoments[i].cwiseProduct(toPrincipal.conjugate() * state.angularVelocities[i]);
  if (momentum != nullptr) *momentum = toPrincipal * bodyMomentum;
  return (rotatePrincipalFrame(toPrincipal, bodyMomentum, state.principalMoments[i], h) *
          state.principalFrames[i].conjugate())
      .normalized();
}

}  // namespace coulomb::integrators
