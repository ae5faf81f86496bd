#pragma once
// The per-block nonsmooth function of a Newton solver and its generalized Jacobian blocks
// A = dPhi/du, B = dPhi/dr (docs/solver-derivations.md (5.5): J = A W + B). Alart-Curnier
// implements it here; Fischer-Burmeister (docs/solver-derivations.md 6.7) slots in as another
// implementation of the same interface: everything else (assembly, regularization, line search,
// stopping) is shared.
#include <coulomb/solvers/ContactProblem.hpp>

#include <Eigen/Core>

namespace coulomb::solvers {

class NewtonFunction {
 public:
  virtual ~NewtonFunction() = default;
  [[nodiscard]] virtual const char* name() const = 0;
  // Contact block with friction coefficient mu and steps rhoN, rhoT > 0.
  virtual void contact(const Eigen::Vector3d& r, const Eigen::Vector3d& u, double mu, double rhoN,
                       double rhoT, Eigen::Vector3d& phi, Eigen::Matrix3d& A,
                       Eigen::Matrix3d& B) const = 0;
  // Scalar row: Phi_i = r_i - P_C(r_i - rho u_i), docs/solver-derivations.md (10.2). Interior
  // (always for equality rows): A = rho, B = 0; at a bound: A = 0, B = 1.
  virtual void scalarRow(const ConstraintBlock& block, double r, double u, double rho, double& phi,
                         double& A, double& B) const;
};

// Alart-Curnier, docs/solver-derivations.md (5.1), radius (5.2a) delta = mu [y_N]_+ (AC91, Siconos
// "STD"), or (5.2b) delta = mu r_N (AC11 eq. (4b) as the paper's section 4.3 intends; the text
// extraction prints mu rho_N). Phi = -f_AC of AC11 (4a)-(4b); blocks (5.3a)-(5.4c).
class AlartCurnierFunction final : public NewtonFunction {
 public:
  enum class Radius { PositivePart, NormalImpulse };  // (5.2a), (5.2b)
  explicit AlartCurnierFunction(Radius radius = Radius::PositivePart) : radius_(radius) {}
  [[nodiscard]] const char* name() const override { return "alart_curnier"; }
  void contact(const Eigen::Vector3d& r, const Eigen::Vector3d& u, double mu, double rhoN,
               double rhoT, Eigen::Vector3d& phi, Eigen::Matrix3d& A,
               Eigen::Matrix3d& B) const override;

 private:
  Radius radius_;
};

}  // namespace coulomb::solvers
