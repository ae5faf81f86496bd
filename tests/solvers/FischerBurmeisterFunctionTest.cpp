#include <gtest/gtest.h>
#include <coulomb/solvers/CoulombLaw.hpp>
#include <coulomb/solvers/newton/FischerBurmeisterFunction.hpp>

#include <random>

using namespace coulomb::solvers;

namespace {

Eigen::Vector3d phiOf(const Eigen::Vector3d& r, const Eigen::Vector3d& u, double mu, double rho) {
  Eigen::Vector3d phi;
  Eigen::Matrix3d A, B;
  FischerBurmeisterFunction().contact(r, u, mu, rho, rho, phi, A, B);
  return phi;
}

}  // namespace

// (6.4): Phi = 0 exactly on the three regimes of (1.6), Phi != 0 off them.
TEST(FischerBurmeisterFunction, ZerosAreCoulombPairs) {
  const double mu = 0.5, rho = 0.7;
  const Eigen::Vector3d takeOffR = Eigen::Vector3d::Zero(), takeOffU(0.3, 1.0, -2.0);
  const Eigen::Vector3d stickR(1.0, 0.2, -0.1), stickU = Eigen::Vector3d::Zero();
  const Eigen::Vector3d slipU(0.0, 0.6, -0.8);                        // unit tangent
  const Eigen::Vector3d slipR(2.0, -mu * 2.0 * 0.6, mu * 2.0 * 0.8);  // r_T = -mu r_N u_T/|u_T|
  EXPECT_LT(phiOf(takeOffR, takeOffU, mu, rho).norm(), 1e-15);
  EXPECT_LT(phiOf(stickR, stickU, mu, rho).norm(), 1e-15);
  EXPECT_LT(phiOf(slipR, slipU, mu, rho).norm(), 1e-15);
  EXPECT_GT(phiOf(slipR, Eigen::Vector3d(0.0, -0.6, 0.8), mu, rho).norm(), 0.1);  // wrong way
  EXPECT_GT(phiOf(stickR, Eigen::Vector3d(-0.1, 0, 0), mu, rho).norm(), 1e-3);    // approaching
}

// (6.5): at a grazing take-off the naive z_0 - |z_bar| loses everything; the det form does not.
TEST(FischerBurmeisterFunction, SmallEigenvalueWithoutCancellation) {
  const Eigen::Vector3d x = Eigen::Vector3d::Zero();
  const Eigen::Vector3d y(1.0, 0.6, 0.8);  // on the boundary of K_1: lambda_1 = 0
  EXPECT_EQ(smallSpectralValue(x, y), 0.0);
  const LorentzFischerBurmeister fb = lorentzFischerBurmeister(x, y);
  EXPECT_LT(fb.phi.norm(), 1e-15);
  const Eigen::Vector3d y2(1.0 + 1e-12, 0.6, 0.8);  // just inside: lambda_1 ~ 4e-24
  EXPECT_GT(smallSpectralValue(x, y2), 0.0);
  EXPECT_LT(lorentzFischerBurmeister(x, y2).phi.norm(), 1e-15);
}

// (6.6)-(6.7): A, B against central differences of Phi(r, u) at smooth random points.
TEST(FischerBurmeisterFunction, JacobianMatchesDifferences) {
  std::mt19937 rng(3);
  std::normal_distribution<double> g(0.0, 1.0);
  double worst = 0;
  for (int k = 0; k < 200; ++k) {
    const double mu = k % 10 == 0 ? 0.0 : 0.1 + std::abs(g(rng));
    const double rho = 0.5 + std::abs(g(rng));
    const Eigen::Vector3d r(g(rng), g(rng), g(rng)), u(g(rng), g(rng), g(rng));
    Eigen::Vector3d phi;
    Eigen::Matrix3d A, B;
    FischerBurmeisterFunction().contact(r, u, mu, rho, rho, phi, A, B);
    const double h = 1e-6;
    for (int j = 0; j < 3; ++j) {
      const Eigen::Vector3d e = Eigen::Vector3d::Unit(j) * h;
      const Eigen::Vector3d dr = (phiOf(r + e, u, mu, rho) - phiOf(r - e, u, mu, rho)) / (2 * h);
      const Eigen::Vector3d du = (phiOf(r, u + e, mu, rho) - phiOf(r, u - e, mu, rho)) / (2 * h);
      worst = std::max(worst, (dr - B.col(j)).norm() / (1 + dr.norm()));
      worst = std::max(worst, (du - A.col(j)).norm() / (1 + du.norm()));
    }
  }
  EXPECT_LT(worst, 1e-6);
}

TEST(FischerBurmeisterFunction, FrictionlessUsesScalarForm) {
  // mu = 0: r_N = 0, u_N > 0 is a zero; Phi_T = r_T.
  const Eigen::Vector3d phi = phiOf({0.0, 0.3, 0.0}, {2.0, 5.0, 1.0}, 0.0, 1.0);
  EXPECT_DOUBLE_EQ(phi[0], 0.0);
  EXPECT_DOUBLE_EQ(phi[1], 0.3);
}
