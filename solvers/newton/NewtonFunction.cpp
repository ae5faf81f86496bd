#include <coulomb/solvers/newton/NewtonFunction.hpp>

#include <coulomb/solvers/CoulombLaw.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace coulomb::solvers {

void NewtonFunction::scalarRow(const ConstraintBlock& block, double r, double u, double rho,
                               double& phi, double& A, double& B) const {
  const double y = r - rho * u;
  double lo = -std::numeric_limits<double>::infinity(), hi = -lo;
  if (block.kind == BlockKind::Unilateral) lo = 0.0;
  if (block.kind == BlockKind::Bounded) lo = block.lower, hi = block.upper;
  if (y > lo && y < hi) {  // interior: Phi = rho u
    phi = rho * u;
    A = rho;
    B = 0.0;
  } else {  // at a bound: Phi = r - bound
    phi = r - (y <= lo ? lo : hi);
    A = 0.0;
    B = 1.0;
  }
}

void AlartCurnierFunction::contact(const Eigen::Vector3d& r, const Eigen::Vector3d& u, double mu,
                                   double rhoN, double rhoT, Eigen::Vector3d& phi,
                                   Eigen::Matrix3d& A, Eigen::Matrix3d& B) const {
  A.setZero();
  B.setZero();
  const double yN = r[0] - rhoN * u[0];  // (5.1)
  const Eigen::Vector2d yT(r[1] - rhoT * u[1], r[2] - rhoT * u[2]);
  if (yN > 0) {  // (5.3a) normal active: Phi_N = rho_N u_N
    phi[0] = rhoN * u[0];
    A(0, 0) = rhoN;
  } else {  // (5.3b) inactive: Phi_N = r_N
    phi[0] = r[0];
    B(0, 0) = 1.0;
  }
  const double delta =
      radius_ == Radius::PositivePart ? mu * std::max(yN, 0.0) : mu * r[0];  // (5.2a)/(5.2b)
  const double ny = tangentNorm(yT[0], yT[1]);  // std::hypot's scaling only where it is needed
  if (ny <= delta) {                            // (5.4a) stick: Phi_T = rho_T u_T
    phi[1] = rhoT * u[1];
    phi[2] = rhoT * u[2];
    A(1, 1) = A(2, 2) = rhoT;
  } else if (delta > 0) {  // (5.4b) slip: Phi_T = r_T - delta yhat
    const Eigen::Vector2d yhat = yT / ny;
    phi[1] = r[1] - delta * yhat[0];
    phi[2] = r[2] - delta * yhat[1];
    const Eigen::Matrix2d gamma = (Eigen::Matrix2d::Identity() - yhat * yhat.transpose()) / ny;
    A.block<2, 2>(1, 1) = rhoT * delta * gamma;
    B.block<2, 2>(1, 1) = Eigen::Matrix2d::Identity() - delta * gamma;
    if (radius_ == Radius::PositivePart) {
      A.block<2, 1>(1, 0) = mu * rhoN * yhat;
      B.block<2, 1>(1, 0) = -mu * yhat * (yN > 0 ? 1.0 : 0.0);
    } else {
      B.block<2, 1>(1, 0) = -mu * yhat;
    }
  } else {  // (5.4c) zero radius: Phi_T = r_T
    phi[1] = r[1];
    phi[2] = r[2];
    B(1, 1) = B(2, 2) = 1.0;
  }
}

}  // namespace coulomb::solvers
