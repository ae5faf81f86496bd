#include <coulomb/solvers/newton/FischerBurmeisterFunction.hpp>

#include <cmath>

namespace coulomb::solvers {

namespace {

// det v = (v_0 - ||v_bar||)(v_0 + ||v_bar||) (6.5), factored to keep its sign exact.
double lorentzDet(const Eigen::Vector3d& v) {
  const double t = std::hypot(v[1], v[2]);
  return (v[0] - t) * (v[0] + t);
}

// L_v = [[v_0, v_bar^T], [v_bar, v_0 I_2]] (6.2).
Eigen::Matrix3d arrow(const Eigen::Vector3d& v) {
  Eigen::Matrix3d L;
  L << v[0], v[1], v[2], v[1], v[0], 0.0, v[2], 0.0, v[0];
  return L;
}

// Scalar FB r + y - sqrt(r^2 + y^2) without cancellation when r + y > 0, and its derivatives.
void scalarFischerBurmeister(double a, double b, double& phi, double& da, double& db) {
  const double s = std::hypot(a, b);
  if (s == 0.0) {
    phi = 0.0;
    da = db = 1.0 - 1.0 / std::sqrt(2.0);  // (6.6c) pragmatic element of the Jacobian
    return;
  }
  phi = a + b > 0 ? 2.0 * a * b / (a + b + s) : a + b - s;
  da = 1.0 - a / s;
  db = 1.0 - b / s;
}

}  // namespace

double smallSpectralValue(const Eigen::Vector3d& x, const Eigen::Vector3d& y) {
  const double z0 = x.squaredNorm() + y.squaredNorm();
  const Eigen::Vector2d zbar = 2.0 * (x[0] * x.tail<2>() + y[0] * y.tail<2>());
  const double lambda2 = z0 + std::hypot(zbar[0], zbar[1]);
  if (lambda2 <= 0.0) return 0.0;
  const Eigen::Vector2d cross = x[0] * y.tail<2>() - y[0] * x.tail<2>();
  const double detSum = lorentzDet(x) + lorentzDet(y);
  const double detZ = detSum * detSum + 4.0 * cross.squaredNorm();  // (6.5)
  return detZ / lambda2;
}

LorentzFischerBurmeister lorentzFischerBurmeister(const Eigen::Vector3d& x,
                                                  const Eigen::Vector3d& y) {
  LorentzFischerBurmeister out;
  const double z0 = x.squaredNorm() + y.squaredNorm();
  const Eigen::Vector2d zbar = 2.0 * (x[0] * x.tail<2>() + y[0] * y.tail<2>());
  const double zbarNorm = std::hypot(zbar[0], zbar[1]);
  const double lambda2 = z0 + zbarNorm;
  if (lambda2 <= 0.0) {  // x = y = 0
    out.phi.setZero();
    out.dx = out.dy = (1.0 - 1.0 / std::sqrt(2.0)) * Eigen::Matrix3d::Identity();
    return out;
  }
  const double lambda1 = std::max(0.0, smallSpectralValue(x, y));
  // (6.3): sqrt z = sqrt(l1) c1 + sqrt(l2) c2, c_{1,2} = (1, -/+ w_bar) / 2.
  const Eigen::Vector2d wbar =
      zbarNorm > 0 ? Eigen::Vector2d(zbar / zbarNorm) : Eigen::Vector2d(1.0, 0.0);
  auto squareRoot = [&](double l1, double l2) {
    const double s1 = std::sqrt(l1), s2 = std::sqrt(l2);
    Eigen::Vector3d w;
    w[0] = 0.5 * (s1 + s2);
    w.tail<2>() = 0.5 * (s2 - s1) * wbar;
    return w;
  };
  const Eigen::Vector3d w = squareRoot(lambda1, lambda2);
  out.phi = x + y - w;
  // (6.6): dphi/dx = I - L_w^-1 L_x; at degenerate points use z + 1e-12 lambda2 e (6.6c).
  double l1 = lambda1, l2 = lambda2;
  if (l1 <= 1e-12 * lambda2) l1 += 1e-12 * lambda2, l2 += 1e-12 * lambda2;
  const Eigen::Vector3d ws = (l1 == lambda1) ? w : squareRoot(l1, l2);
  const double detW = std::sqrt(l1) * std::sqrt(l2);
  Eigen::Matrix3d Linv;
  const Eigen::Vector2d wb = ws.tail<2>();
  Linv(0, 0) = ws[0];
  Linv.block<1, 2>(0, 1) = -wb.transpose();
  Linv.block<2, 1>(1, 0) = -wb;
  Linv.block<2, 2>(1, 1) =
      (detW / ws[0]) * Eigen::Matrix2d::Identity() + wb * wb.transpose() / ws[0];
  Linv /= detW;
  out.dx = Eigen::Matrix3d::Identity() - Linv * arrow(x);
  out.dy = Eigen::Matrix3d::Identity() - Linv * arrow(y);
  return out;
}

void FischerBurmeisterFunction::contact(const Eigen::Vector3d& r, const Eigen::Vector3d& u,
                                        double mu, double rhoN, double /*rhoT*/,
                                        Eigen::Vector3d& phi, Eigen::Matrix3d& A,
                                        Eigen::Matrix3d& B) const {
  A.setZero();
  B.setZero();
  const double rho = rhoN;
  if (mu < 1e-6) {  // frictionless: scalar FB on (r_N, rho u_N), Phi_T = r_T
                    // (docs/solver-derivations.md 6)
    double da = 0, db = 0;
    scalarFischerBurmeister(r[0], rho * u[0], phi[0], da, db);
    B(0, 0) = da;
    A(0, 0) = rho * db;
    phi[1] = r[1];
    phi[2] = r[2];
    B(1, 1) = B(2, 2) = 1.0;
    return;
  }
  const double ut = std::hypot(u[1], u[2]);
  const Eigen::Vector3d x(mu * r[0], r[1], r[2]);  // (6.1)
  const Eigen::Vector3d y(rho * (u[0] + mu * ut), rho * mu * u[1], rho * mu * u[2]);
  const LorentzFischerBurmeister fb = lorentzFischerBurmeister(x, y);
  phi = fb.phi;
  // (6.7): A = rho (dphi/dy) D, B = (dphi/dx) S, S = diag(mu, 1, 1).
  Eigen::Matrix3d D = Eigen::Matrix3d::Zero();
  D(0, 0) = 1.0;
  if (ut > 0) D(0, 1) = mu * u[1] / ut, D(0, 2) = mu * u[2] / ut;
  D(1, 1) = D(2, 2) = mu;
  A = rho * fb.dy * D;
  B = fb.dx;
  B.col(0) *= mu;
}

}  // namespace coulomb::solvers
