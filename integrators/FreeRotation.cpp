#include <coulomb/geometry/Quaternion.hpp>
#include <coulomb/integrators/FreeRotation.hpp>

namespace coulomb::integrators {

Eigen::Quaterniond rotateTorqueFree(const Eigen::Quaterniond& orientation,
                                    const Eigen::Quaterniond& principalFrame,
                                    const Eigen::Vector3d& principalMoments,
                                    const Eigen::Vector3d& angularMomentum, double h) {
  // Q: principal axes -> world. The body momentum pi = Q^T L; the flow of T_k = pi_k^2/(2 I_k)
  // is Q <- Q R_k(t pi_k / I_k), pi <- R_k^T pi (DLM 1997, eqs. 3.5-3.7), so L = Q pi is unchanged.
  Eigen::Quaterniond q = orientation * principalFrame;
  Eigen::Vector3d pi = q.conjugate() * angularMomentum;
  const auto subRotation = [&](int axis, double step) {
    const Eigen::Quaterniond r =
        geometry::axisRotation(axis, step * pi[axis] / principalMoments[axis]);
    q = q * r;
    pi = r.conjugate() * pi;
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
  return (q * principalFrame.conjugate()).normalized();
}

}  // namespace coulomb::integrators
