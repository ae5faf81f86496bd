#pragma once
// Fischer-Burmeister function for second-order cones (docs/solver-derivations.md section 6;
// Fukushima, Luo, Tseng, SIAM J. Optim. 12(2) 2002) as a NewtonFunction: per contact, with the De
// Saxce mapping (6.1)
//   x = (mu r_N, r_T),  y = rho (u_N + mu ||u_T||, mu u_T),  Phi_c = x + y - sqrt(x o x + y o y)
// (Jordan product (6.2), spectral square root (6.3)), whose zeros are exactly the Coulomb law
// (6.4). The small eigenvalue is computed without cancellation (6.5); the Jacobian blocks are
// (6.6)-(6.7), smoothed at degenerate points (6.6c). mu < 1e-6: scalar FB on the normal and
// Phi_T = r_T. Scalar rows keep the natural map of NewtonFunction (docs/solver-derivations.md
// section 10).
#include <coulomb/solvers/newton/NewtonFunction.hpp>

namespace coulomb::solvers {

// phi(x, y) and its partial Jacobians for x, y in R^3 (Lorentz cone K_1 = {||x_bar|| <= x_0}).
struct LorentzFischerBurmeister {
  Eigen::Vector3d phi;
  Eigen::Matrix3d dx;  // d phi / d x
  Eigen::Matrix3d dy;  // d phi / d y
};
LorentzFischerBurmeister lorentzFischerBurmeister(const Eigen::Vector3d& x,
                                                  const Eigen::Vector3d& y);

// The smallest spectral value of z = x o x + y o y by (6.5): det(z) / (z_0 + ||z_bar||) with
// det(z) = (det x + det y)^2 + 4 ||x_0 y_bar - y_0 x_bar||^2 (exposed for tests).
double smallSpectralValue(const Eigen::Vector3d& x, const Eigen::Vector3d& y);

class FischerBurmeisterFunction final : public NewtonFunction {
 public:
  [[nodiscard]] const char* name() const override { return "fischer_burmeister"; }
  // rhoN is the rho_c of (6.1) (one step per contact); rhoT is unused.
  void contact(const Eigen::Vector3d& r, const Eigen::Vector3d& u, double mu, double rhoN,
               double rhoT, Eigen::Vector3d& phi, Eigen::Matrix3d& A,
               Eigen::Matrix3d& B) const override;
};

}  // namespace coulomb::solvers
