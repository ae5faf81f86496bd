#pragma once
// The one problem every solver solves (docs/architecture.md section 4, docs/solver-derivations.md
// (1.1)-(1.5), (10.1)): find r with u = W r + q and, block by block,
//   Equality    u_i = 0, r_i free                       (bilateral joint rows)
//   Bounded     lower <= r_i <= upper, box complementarity (motors, joint friction)
//   Unilateral  0 <= r_i  _|_  u_i >= 0                   (limits, frictionless contacts)
//   Contact3D   (N, T1, T2): K* ∋ u + mu ||u_T|| e_N  _|_  r ∈ K, K the exact Coulomb cone
//               (isotropic mu, or anisotropic mu1, mu2 along T1, T2).
// Units: r impulses [N s], u and q velocities [m/s], W inverse mass [1/kg].
#include <coulomb/solvers/DelassusOperator.hpp>

#include <Eigen/Core>

#include <algorithm>
#include <limits>
#include <optional>
#include <string>
#include <vector>

namespace coulomb::solvers {

enum class BlockKind { Equality, Bounded, Unilateral, Contact3D };
const char* blockKindName(BlockKind kind);

struct ConstraintBlock {
  BlockKind kind = BlockKind::Contact3D;
  double mu = 0.0;              // Contact3D, isotropic friction coefficient [-]
  bool anisotropic = false;     // Contact3D: use mu1, mu2 instead of mu
  double mu1 = 0.0, mu2 = 0.0;  // Contact3D anisotropic coefficients along T1, T2 [-]
  double lower = -std::numeric_limits<double>::infinity();  // Bounded [N s]
  double upper = std::numeric_limits<double>::infinity();   // Bounded [N s]

  static ConstraintBlock equality() { return {BlockKind::Equality}; }
  static ConstraintBlock bounded(double lo, double hi) {
    ConstraintBlock b{BlockKind::Bounded};
    b.lower = lo;
    b.upper = hi;
    return b;
  }
  static ConstraintBlock unilateral() { return {BlockKind::Unilateral}; }
  static ConstraintBlock contact(double mu) {
    ConstraintBlock b{BlockKind::Contact3D};
    b.mu = mu;
    return b;
  }
  static ConstraintBlock anisotropicContact(double mu1, double mu2) {
    ConstraintBlock b{BlockKind::Contact3D};
    b.anisotropic = true;
    b.mu1 = mu1;
    b.mu2 = mu2;
    b.mu = std::max(mu1, mu2);
    return b;
  }
  [[nodiscard]] int size() const { return kind == BlockKind::Contact3D ? 3 : 1; }
  [[nodiscard]] bool isContact() const { return kind == BlockKind::Contact3D; }
};

struct ContactProblem {
  std::string name;                          // for reports (e.g. the fc3d name)
  DelassusOperator W;                        // size() x size()
  Eigen::VectorXd q;                         // size()
  std::vector<ConstraintBlock> blocks;       // in the order of the unknowns
  std::optional<Eigen::VectorXd> warmStart;  // size(): initial r (e.g. last step's impulses)
  // Empty, or 6 per body of a body-space W (its body order; linear, angular): the bodies'
  // velocities at the step's start, before the step's forces (v_k). J v_k are the rows'
  // velocities the bodies arrived with; on a resting body, the error the last solve left within
  // its tolerance, which an exact answer removes once and which a warm start must not repeat
  // (SolveOutcome::nextWarmStart).
  Eigen::VectorXd arrival;

  // A pure contact problem (fc3d): n contacts with coefficients mu.
  static ContactProblem contacts(DelassusOperator W, Eigen::VectorXd q,
                                 const std::vector<double>& mu, std::string name = {});

  [[nodiscard]] int size() const;          // number of scalar unknowns
  [[nodiscard]] int contactCount() const;  // number of Contact3D blocks
  [[nodiscard]] std::vector<int> blockSizes() const;
  [[nodiscard]] std::vector<int> blockOffsets() const;  // blockCount() + 1 entries

  // The first broken invariant, named (sizes, square W, non-finite entry, mu < 0, bounds,
  // W diagonal not positive), or nullopt when the problem is well formed. A matrix-free W is
  // checked column by column (one product per unknown).
  [[nodiscard]] std::optional<std::string> validate() const;
};

}  // namespace coulomb::solvers
