#pragma once
// Problems made of equality rows only (a joint island without limits, motors or contacts): the
// linear system W r = -q solved directly by a sparse LDL^T factorization (SparseLdlt: approximate
// minimum degree ordering, analysed once per pattern, then factorizations without allocation). For
// a joint island whose bodies and joints form a tree (a chain, a rope, a branching mechanism), W =
// J M^-1 J^T couples only joints that share a body, and the elimination ordering follows the tree
// with no fill-in beyond the body cliques: linear time in the number of joints, the direct solve of
// Baraff 1996 ("Linear-time dynamics using Lagrange multipliers", section 7) in Delassus form. A
// loop (redundant rows, W singular) may factor with a tiny pivot: the common residual then decides,
// and the plan's fallback (ac_newton) takes over. Rows that come in threes with one pattern (ball
// joints: chains, ropes) are factorized by 3 x 3 blocks (BlockLdlt), several times cheaper than
// entry by entry.
#include <coulomb/solvers/BodySpaceDelassus.hpp>
#include <coulomb/solvers/ContactSolver.hpp>
#include <coulomb/solvers/direct/BlockLdlt.hpp>
#include <coulomb/solvers/direct/SparseLdlt.hpp>

#include <utility>
#include <vector>

namespace coulomb::solvers {

class EqualityLdltSolver final : public ContactSolver {
 public:
  [[nodiscard]] std::string name() const override { return "ldlt"; }
  [[nodiscard]] bool ignoresStart() const override { return true; }
  // On body-space factors the 3 x 3 blocks are formed from J and M^-1 J^T directly (W's entries
  // only for rows that do not come in threes).
  [[nodiscard]] bool worksInBodySpace() const override { return true; }
  [[nodiscard]] std::optional<std::string> notApplicable(
      const ContactProblem& problem) const override;
  void solvePrepared(const PreparedProblem& problem, const SolveContext& context,
                     Eigen::VectorXd& r, SolverReport& report) const override;

 private:
  // The scalar path: W's lower triangle as entries, factorized by workspace_.ldlt.
  bool factorizeByEntries(const BlockSparseMatrix& W, int n) const;
  // W as 3 x 3 blocks (workspace_.pairs, diagonal, coupling) when its rows come in threes: from
  // W's entries, or from body-space factors. False when they do not.
  bool blocksFromEntries(const BlockSparseMatrix& W, int n) const;
  bool blocksFromFactors(const BodySpaceDelassus& factors) const;
  // The pattern of those blocks and the products that sum them, from the groups' bodies.
  void productsFromBodies(const BodySpaceDelassus& factors, int groups) const;
  struct Workspace {  // kept between solves (ContactSolver::solve: one instance, one thread)
    SparseLdlt ldlt;
    std::vector<int> rows, cols;
    std::vector<double> values;
    BlockLdltOf<3> blockLdlt;  // rows in threes
    std::vector<std::pair<int, int>> pairs;
    std::vector<BlockLdltOf<3>::Block> diagonal, coupling;
    // blocksFromFactors: the bodies of each group (the pattern's identity), the groups per body,
    // and the products J_g M^-1 J_h^T on a shared body that sum into each block.
    struct Product {
      int g, h, sideG, sideH, target;  // target: diagonal[target], or coupling[target - groups]
    };
    std::vector<int> groupBodies, bodyStart, bodyGroups, next, lower;
    std::vector<Product> products;
    Eigen::VectorXd rhs, x, u;
  };
  mutable Workspace workspace_;
};

}  // namespace coulomb::solvers
