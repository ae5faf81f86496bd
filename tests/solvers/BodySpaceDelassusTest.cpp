// BodySpaceDelassus: W = J M^-1 J^T kept factored. Checked against the global product, and
// Gauss-Seidel on the factors against Gauss-Seidel on the entries (same problem, same answer).
#include <coulomb/solvers/BodySpaceDelassus.hpp>
#include <coulomb/solvers/ContactProblem.hpp>
#include <coulomb/solvers/DelassusOperator.hpp>
#include <coulomb/solvers/bgs/BgsSolver.hpp>
#include <coulomb/solvers/pgs/PgsSolver.hpp>

#include <gtest/gtest.h>
#include <Eigen/Dense>

#include <limits>
#include <memory>
#include <random>
#include <stdexcept>
#include <vector>

using namespace coulomb::solvers;

namespace {

// A chain of `bodies` bodies, contact c between body c-1 and c (body -1 = ground), plus one
// scalar row on the last body: J (rows x 6 bodies), block-diagonal SPD M^-1, and the factors.
struct Chain {
  Eigen::MatrixXd J, Minv;
  std::shared_ptr<BodySpaceDelassus> factors;
  std::vector<int> sizes;
};

Chain chain(int bodies, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> g(0.0, 1.0);
  Chain c;
  c.sizes.assign(bodies, 3);
  c.sizes.push_back(1);
  const int rows = 3 * bodies + 1, dofs = 6 * bodies;
  c.J = Eigen::MatrixXd::Zero(rows, dofs);
  c.Minv = Eigen::MatrixXd::Zero(dofs, dofs);
  for (int b = 0; b < bodies; ++b) {
    Eigen::Matrix<double, 6, 6> L;
    for (int i = 0; i < 6; ++i)
      for (int j = 0; j < 6; ++j) L(i, j) = 0.3 * g(rng);
    c.Minv.block<6, 6>(6 * b, 6 * b) =
        (L * L.transpose() + Eigen::Matrix<double, 6, 6>::Identity()).inverse();
  }
  c.factors = std::make_shared<BodySpaceDelassus>(bodies, c.sizes);
  for (int k = 0; k <= bodies; ++k) {
    const int height = k < bodies ? 3 : 1, row = 3 * k;
    const int lower = k < bodies ? k - 1 : bodies - 1, upper = k < bodies ? k : -1;
    for (const auto& [side, body] : {std::pair{0, lower}, std::pair{1, upper}}) {
      if (body < 0) continue;
      Eigen::MatrixXd Jb(height, 6);
      for (int i = 0; i < height; ++i)
        for (int j = 0; j < 6; ++j) Jb(i, j) = g(rng);
      c.J.block(row, 6 * body, height, 6) = Jb;
      const Eigen::MatrixXd G = c.Minv.block<6, 6>(6 * body, 6 * body) * Jb.transpose();
      c.factors->setSide(k, side, body, Jb, G);
    }
  }
  return c;
}

}  // namespace

TEST(BodySpaceDelassus, ProductEntriesDiagonalAndRowsMatchTheGlobalProduct) {
  const Chain c = chain(5, 3);
  const Eigen::MatrixXd W = c.J * c.Minv * c.J.transpose();
  const Eigen::VectorXd x = Eigen::VectorXd::LinSpaced(W.rows(), -1.0, 1.5);
  Eigen::VectorXd y = Eigen::VectorXd::Ones(W.rows());
  c.factors->multiplyAdd(x, y);
  EXPECT_LT((y - (W * x + Eigen::VectorXd::Ones(W.rows()))).norm(), 1e-12);
  EXPECT_LT((c.factors->toBlockSparse().toDense() - W).norm(), 1e-12);
  // Blocks 0 and 2 share no body: their block is not stored.
  const BlockSparseMatrix& entries = c.factors->toBlockSparse();
  for (int k = entries.rowBegin(0); k < entries.rowEnd(0); ++k)
    EXPECT_NE(entries.blockColumn(k), 2);
  double d[9];
  c.factors->diagonalBlock(2, d);
  EXPECT_LT(
      (Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(d) - W.block<3, 3>(6, 6))
          .norm(),
      1e-12);
  const std::vector<int> rows{0, 6, 15};  // two normal rows and the scalar row
  const BodySpaceDelassus normal = c.factors->selectRows(rows);
  Eigen::MatrixXd Wnn(3, 3);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) Wnn(i, j) = W(rows[i], rows[j]);
  EXPECT_LT((normal.toBlockSparse().toDense() - Wnn).norm(), 1e-12);
  EXPECT_TRUE(c.factors->allFinite());
  EXPECT_THROW(
      c.factors->setSide(0, 0, 7, Eigen::MatrixXd::Zero(3, 6), Eigen::MatrixXd::Zero(6, 3)),
      std::invalid_argument);
}

TEST(BodySpaceDelassus, GaussSeidelOnTheFactorsSolvesWhatItSolvesOnTheEntries) {
  const Chain c = chain(8, 11);
  Eigen::VectorXd q = c.J * Eigen::VectorXd::LinSpaced(c.J.cols(), -1.0, 1.0);
  for (int k = 0; k < 8; ++k) q[3 * k] -= 1.0;  // approaching contacts
  std::vector<ConstraintBlock> blocks(8, ConstraintBlock::contact(0.5));
  blocks.push_back(ConstraintBlock::bounded(-0.2, 0.3));
  ContactProblem factored;
  factored.W = DelassusOperator::bodySpace(c.factors);
  factored.q = q;
  factored.blocks = blocks;
  ContactProblem entries = factored;
  entries.W = DelassusOperator::blockSparse(c.factors->toBlockSparse());
  ASSERT_FALSE(factored.validate().has_value());
  SolverOptions options;
  options.tolerance = 1e-10;
  std::vector<std::unique_ptr<ContactSolver>> solvers;
  solvers.push_back(std::make_unique<PgsSolver>());
  solvers.push_back(std::make_unique<BgsSolver>());
  for (const auto& solver : solvers) {
    const SolveOutcome a = solver->solve(factored, options);
    const SolveOutcome b = solver->solve(entries, options);
    EXPECT_TRUE(a.report.converged()) << solver->name() << " " << a.report.residual;
    EXPECT_TRUE(b.report.converged()) << solver->name();
    EXPECT_LE(a.report.residual, 1e-10);
    // The same iteration up to round-off: the same number of sweeps and the same answer.
    EXPECT_NEAR(a.report.iterations, b.report.iterations, 1) << solver->name();
    EXPECT_LT((a.impulses - b.impulses).norm(), 1e-7 * (1.0 + b.impulses.norm()));
  }
}

TEST(BodySpaceDelassus, RejectsBadShapes) {
  EXPECT_THROW(BodySpaceDelassus(2, {3, 2}), std::invalid_argument);
  EXPECT_THROW(BodySpaceDelassus(-1, {3}), std::invalid_argument);
}

// The assembler's raw setSide (J rows of 6, M^-1 J^T columns of 6) stores what the Ref one
// stores; the cached diagonal blocks follow a later setSide; allFinite sees inf and NaN.
TEST(BodySpaceDelassus, RawSidesCachedDiagonalAndFiniteness) {
  const Chain c = chain(4, 5);
  BodySpaceDelassus raw(4, c.sizes);
  for (int k = 0; k < raw.blockCount(); ++k) {
    const int height = c.sizes[k], row = raw.blockOffset(k);
    for (int side = 0; side < 2; ++side) {
      const int body = k < 4 ? (side == 0 ? k - 1 : k) : (side == 0 ? 3 : -1);
      if (body < 0) continue;
      const Eigen::Matrix<double, Eigen::Dynamic, 6, Eigen::RowMajor> Jb =
          c.J.block(row, 6 * body, height, 6);
      const Eigen::MatrixXd G = c.Minv.block<6, 6>(6 * body, 6 * body) * Jb.transpose();
      raw.setSide(k, side, body, Jb.data(), G.data());
    }
  }
  const Eigen::VectorXd x = Eigen::VectorXd::LinSpaced(raw.size(), -1.0, 2.0);
  Eigen::VectorXd y1 = Eigen::VectorXd::Zero(raw.size()), y2 = y1;
  raw.multiplyAdd(x, y1);
  c.factors->multiplyAdd(x, y2);
  EXPECT_EQ(y1, y2);  // same numbers stored, same operations
  EXPECT_EQ(raw.toBlockSparse().toDense(), c.factors->toBlockSparse().toDense());

  double before[9], after[9];
  raw.diagonalBlock(1, before);
  const Eigen::Matrix<double, 3, 6, Eigen::RowMajor> J2 =
      2.0 * Eigen::Matrix<double, 3, 6, Eigen::RowMajor>::Ones();
  const Eigen::Matrix<double, 6, 3> G2 = Eigen::Matrix<double, 6, 3>::Ones();
  raw.setSide(1, 0, 0, J2.data(), G2.data());
  raw.diagonalBlock(1, after);
  EXPECT_NE(after[0], before[0]);
  const Eigen::MatrixXd W = raw.toBlockSparse().toDense();
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) EXPECT_DOUBLE_EQ(after[3 * a + b], W(3 + a, 3 + b));

  EXPECT_TRUE(raw.allFinite());
  Eigen::Matrix<double, 3, 6, Eigen::RowMajor> bad = J2;
  bad(2, 5) = std::numeric_limits<double>::infinity();
  raw.setSide(1, 0, 0, bad.data(), G2.data());
  EXPECT_FALSE(raw.allFinite());
  bad(2, 5) = std::numeric_limits<double>::quiet_NaN();
  raw.setSide(1, 0, 0, bad.data(), G2.data());
  EXPECT_FALSE(raw.allFinite());
  raw.setSide(1, 0, 0, J2.data(), G2.data());  // overwritten: finite again
  EXPECT_TRUE(raw.allFinite());
  // A block with one side (a contact on a static body) is checked too, in J and in G.
  const int oneSided = raw.blockCount() - 1;
  const int height = c.sizes[static_cast<std::size_t>(oneSided)];
  Eigen::Matrix<double, Eigen::Dynamic, 6, Eigen::RowMajor> J1 =
      Eigen::Matrix<double, Eigen::Dynamic, 6, Eigen::RowMajor>::Ones(height, 6);
  Eigen::MatrixXd G1 = Eigen::MatrixXd::Ones(6, height);
  G1(5, height - 1) = std::numeric_limits<double>::quiet_NaN();
  raw.setSide(oneSided, 0, 3, J1.data(), G1.data());
  EXPECT_FALSE(raw.allFinite());
  G1(5, height - 1) = 1.0;
  raw.setSide(oneSided, 0, 3, J1.data(), G1.data());
  EXPECT_TRUE(raw.allFinite());
  EXPECT_THROW(raw.setSide(1, 0, 9, J2.data(), G2.data()), std::invalid_argument);
}

// sideCouplings(): each contact's G_s J_t from its sides, as the products of the matrices it was
// given (what the body-space Newton step adds for a sticking contact); cached, and recomputed
// after a side is set.
TEST(BodySpaceDelassus, SideCouplingsAreTheSidesProductsUntilASideIsSet) {
  const Chain c = chain(3, 11);
  BodySpaceDelassus& W = *c.factors;
  const auto expected = [&](int block, int s, int t) {
    const int body[2] = {block - 1, block};  // contact k between bodies k-1 and k
    const Eigen::MatrixXd Js = c.J.block(3 * block, 6 * body[s], 3, 6);
    const Eigen::MatrixXd Jt = c.J.block(3 * block, 6 * body[t], 3, 6);
    const Eigen::MatrixXd Gs = c.Minv.block(6 * body[s], 6 * body[s], 6, 6) * Js.transpose();
    return Eigen::MatrixXd(Gs * Jt);
  };
  for (int block = 1; block < 3; ++block)
    for (int s = 0; s < 2; ++s)
      for (int t = 0; t < 2; ++t) {
        const Eigen::Map<const Eigen::Matrix<double, 6, 6>> got(W.sideCouplings(block) +
                                                                36 * (2 * s + t));
        EXPECT_LT((got - expected(block, s, t)).norm(), 1e-12 * expected(block, s, t).norm())
            << block << s << t;
      }
  const Eigen::Matrix<double, 3, 6, Eigen::RowMajor> J2 =
      Eigen::Matrix<double, 3, 6, Eigen::RowMajor>::Constant(0.5);
  const Eigen::Matrix<double, 6, 3> G2 = Eigen::Matrix<double, 6, 3>::Constant(2.0);
  W.setSide(1, 0, 0, J2.data(), G2.data());
  const Eigen::Map<const Eigen::Matrix<double, 6, 6>> after(W.sideCouplings(1));  // (s, t) = (0, 0)
  EXPECT_LT((after - Eigen::Matrix<double, 6, 6>::Constant(3.0)).norm(), 1e-14);  // 3 x 2 x 0.5
}

// extract(): the blocks of a group on their own bodies. Contacts 3 and 4 of a 6-body chain touch
// bodies 2, 3 and 4 only: the extracted operator has 3 bodies (numbered as the blocks meet them)
// and the same W restricted to those blocks.
TEST(BodySpaceDelassus, ExtractKeepsTheGroupsBlocksOnTheirOwnBodies) {
  const Chain c = chain(6, 5);
  const Eigen::MatrixXd W = c.J * c.Minv * c.J.transpose();
  const int blocks[2] = {3, 4};
  BodySpaceDelassus group(0, {});
  std::vector<int> localOf;
  c.factors->extract(blocks, 2, group, localOf);
  EXPECT_EQ(group.bodyCount(), 3);
  EXPECT_EQ(group.blockCount(), 2);
  EXPECT_EQ(localOf[2], 0);
  EXPECT_EQ(localOf[3], 1);
  EXPECT_EQ(localOf[4], 2);
  EXPECT_EQ(localOf[0], -1);
  EXPECT_EQ(group.blockBody(0, 0), 0);  // contact 3: bodies 2 (side 0) and 3
  EXPECT_EQ(group.blockBody(1, 1), 2);  // contact 4: bodies 3 and 4 (side 1)
  EXPECT_LT((group.toBlockSparse().toDense() - W.block<6, 6>(9, 9)).norm(), 1e-12);
}
