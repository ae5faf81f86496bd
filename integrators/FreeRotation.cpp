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
  subRotation(0, 0.5 * h);
  subRotation(1, 0.5 * h);
  subRotation(2, h);
  subRotation(1, 0.5 * h);
  subRotation(0, 0.5 * h);
  return (q * principalFrame.conjugate()).normalized();
}

}  // namespace coulomb::integrators
