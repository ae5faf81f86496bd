#pragma once
// The exact Coulomb law of one contact, (normal, tangent1, tangent2) ordering
// (docs/solver-derivations.md section 1): cone K = {||x_T|| <= mu x_N}, dual cone K*, De Saxce
// shift u + mu ||u_T|| e_N, projections and the regime classification. The isotropic functions are
// inline: they sit in every solver's inner loop. Anisotropic (elliptic) variants: K = {||M^-1 x_T||
// <= x_N}, M = diag(mu1, mu2).
#include <Eigen/Core>

#include <cmath>

namespace coulomb::solvers {

// sqrt(a^2 + b^2) of a tangential pair, everywhere the Coulomb law is evaluated (sweeps, the
// Alart-Curnier function, the common residual): the plain formula when a^2 + b^2 neither
// overflows nor underflows (then within an ulp or two of std::hypot, which pays for its scaling
// on every call: 24 % of a pgs sweep, 3 % of a small scene's step), std::hypot otherwise.
inline double tangentNorm(double a, double b) {
  const double s = a * a + b * b;
  if (s >= 1e-290 && s <= 1e290) return std::sqrt(s);
  if (a == 0.0 && b == 0.0) return 0.0;
  return std::hypot(a, b);
}

// P_K(x), docs/solver-derivations.md (2.1); the branches and operations of fc3d_project_cone
// (tests/data/fc3d), with tangentNorm for its std::hypot. No division by mu.
inline void projectOntoCone(double x[3], double mu) {
  const double t = tangentNorm(x[1], x[2]);
  if (x[0] >= 0 && t <= mu * x[0]) return;  // (a) inside K (the x_N >= 0 test matters at mu = 0)
  if (mu * t <= -x[0]) {                    // (b) inside the polar cone
    x[0] = x[1] = x[2] = 0.0;
    return;
  }
  const double a = (x[0] + mu * t) / (1.0 + mu * mu);  // (c) onto the boundary ray
  x[0] = a;
  if (t > 0) {
    x[1] *= mu * a / t;
    x[2] *= mu * a / t;
  }
}

inline Eigen::Vector3d projectOntoCone(const Eigen::Vector3d& x, double mu) {
  double v[3] = {x[0], x[1], x[2]};
  projectOntoCone(v, mu);
  return {v[0], v[1], v[2]};
}

// P_{K*}(y), docs/solver-derivations.md (2.2); K* = {mu ||y_T|| <= y_N}.
Eigen::Vector3d projectOntoDualCone(const Eigen::Vector3d& y, double mu);

// P_{D(radius)}(y): disk of the given radius, 0 when radius <= 0, docs/solver-derivations.md (2.5).
inline Eigen::Vector2d projectOntoDisk(const Eigen::Vector2d& y, double radius) {
  if (radius <= 0) return Eigen::Vector2d::Zero();
  const double n = tangentNorm(y[0], y[1]);
  return n <= radius ? y : Eigen::Vector2d(y * (radius / n));
}

// De Saxce shift u + mu ||u_T|| e_N, docs/solver-derivations.md (1.4).
inline Eigen::Vector3d deSaxceShift(const Eigen::Vector3d& u, double mu) {
  return {u[0] + mu * tangentNorm(u[1], u[2]), u[1], u[2]};
}

// Elliptic cone {||(x_T1/mu1, x_T2/mu2)|| <= x_N}, mu1, mu2 >= 0 (a zero coefficient forbids that
// tangent direction). Euclidean projection by a monotone scalar equation in the KKT multiplier
// (derivation in CoulombLaw.cpp); equals projectOntoCone when mu1 = mu2.
Eigen::Vector3d projectOntoEllipticCone(const Eigen::Vector3d& x, double mu1, double mu2);
// Shift for the elliptic cone: u + ||(mu1 u_T1, mu2 u_T2)|| e_N (dual cone ||M y_T|| <= y_N).
inline Eigen::Vector3d deSaxceShift(const Eigen::Vector3d& u, double mu1, double mu2) {
  return {u[0] + std::hypot(mu1 * u[1], mu2 * u[2]), u[1], u[2]};
}

// Regime of a pair (r, u), docs/solver-derivations.md (1.6); `tolerance` is relative to max(||r||,
// ||u||).
enum class ContactRegime { TakeOff, Stick, Slip, Violated };
ContactRegime classifyContact(const Eigen::Vector3d& r, const Eigen::Vector3d& u, double mu,
                              double tolerance = 1e-8);
const char* contactRegimeName(ContactRegime regime);

}  // namespace coulomb::solvers
