#include <coulomb/solvers/CoulombLaw.hpp>

#include <algorithm>

namespace coulomb::solvers {

Eigen::Vector3d projectOntoDualCone(const Eigen::Vector3d& y, double mu) {
  const double t = std::hypot(y[1], y[2]);
  if (mu * t <= y[0]) return y;                         // (a) inside K*
  if (t <= -mu * y[0]) return Eigen::Vector3d::Zero();  // (b) inside -K (polar of K*)
  const double b = (mu * y[0] + t) / (1.0 + mu * mu);   // (c)
  return {mu * b, b * y[1] / t, b * y[2] / t};
}

// Projection onto K = {||M^-1 x_T|| <= x_N}, M = diag(m1, m2) > 0. Outside K and its polar
// {||M x_T|| <= -x_N} the projection is on the boundary. KKT of min ½||r - x||^2 subject to
// ||M^-1 r_T||^2 <= r_N^2 with multiplier l >= 0:
//   r_N = x_N / (1 - l),   r_Ti = x_Ti m_i^2 / (m_i^2 + l),
// and the boundary condition ||M^-1 r_T|| = r_N reads, with w_i(l) = (1 - l)/(m_i^2 + l),
//   g(l) = sign(1 - l) sqrt(sum_i x_Ti^2 m_i^2 w_i(l)^2) - x_N = 0.
// Each w_i decreases strictly from 1/m_i^2 (l = 0) through 0 (l = 1) to -1 (l -> inf), so g is
// strictly decreasing from ||M^-1 x_T|| - x_N > 0 to -||M x_T|| - x_N < 0: one root, bracketed
// and found by bisection to full precision. r_N is then taken as ||M^-1 r_T|| (safe at l = 1).
Eigen::Vector3d projectOntoEllipticCone(const Eigen::Vector3d& x, double mu1, double mu2) {
  if (mu1 == mu2) return projectOntoCone(x, mu1);
  if (mu1 == 0.0 || mu2 == 0.0) {  // a planar cone in (N, the allowed tangent)
    const bool first = mu1 > 0.0;
    const double mu = first ? mu1 : mu2;
    Eigen::Vector3d y(x[0], first ? x[1] : 0.0, first ? 0.0 : x[2]);
    return projectOntoCone(y, mu);
  }
  const double m1s = mu1 * mu1, m2s = mu2 * mu2;
  const double inside = std::hypot(x[1] / mu1, x[2] / mu2);
  if (x[0] >= 0 && inside <= x[0]) return x;
  if (std::hypot(mu1 * x[1], mu2 * x[2]) <= -x[0]) return Eigen::Vector3d::Zero();
  auto g = [&](double l) {
    const double w1 = (1.0 - l) / (m1s + l), w2 = (1.0 - l) / (m2s + l);
    const double s = std::hypot(x[1] * mu1 * w1, x[2] * mu2 * w2);
    return (l <= 1.0 ? s : -s) - x[0];
  };
  double lo = 0.0, hi = 1.0;
  if (x[0] < 0) {
    lo = 1.0;
    hi = 2.0;
    for (int k = 0; k < 2000 && g(hi) > 0; ++k) lo = hi, hi *= 2.0;
  }
  for (int k = 0; k < 200; ++k) {
    const double mid = 0.5 * (lo + hi);
    if (mid <= lo || mid >= hi) break;
    (g(mid) > 0 ? lo : hi) = mid;
  }
  const double l = 0.5 * (lo + hi);
  const double rT1 = x[1] * m1s / (m1s + l), rT2 = x[2] * m2s / (m2s + l);
  return {std::hypot(rT1 / mu1, rT2 / mu2), rT1, rT2};
}

ContactRegime classifyContact(const Eigen::Vector3d& r, const Eigen::Vector3d& u, double mu,
                              double tolerance) {
  const double scale = std::max({r.norm(), u.norm(), 1e-300});
  const double tol = tolerance * scale;
  const double rT = std::hypot(r[1], r[2]), uT = std::hypot(u[1], u[2]);
  if (r.norm() <= tol && u[0] >= -tol) return ContactRegime::TakeOff;
  if (r[0] < -tol || rT > mu * r[0] + tol) return ContactRegime::Violated;
  if (u.norm() <= tol) return ContactRegime::Stick;
  if (std::abs(u[0]) <= tol && std::abs(rT - mu * r[0]) <= tol &&
      (r.tail<2>() + mu * r[0] * u.tail<2>() / uT).norm() <= tol)
    return ContactRegime::Slip;
  return ContactRegime::Violated;
}

const char* contactRegimeName(ContactRegime regime) {
  switch (regime) {
    case ContactRegime::TakeOff:
      return "take-off";
    case ContactRegime::Stick:
      return "stick";
    case ContactRegime::Slip:
      return "slip";
    case ContactRegime::Violated:
      return "violated";
  }
  return "?";
}

}  // namespace coulomb::solvers
