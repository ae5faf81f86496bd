// Impulse-level ABA against M^-1 J^T with M from CRBA, and the Delassus operator built on it.
#include <gtest/gtest.h>
#include <coulomb/joints/tree/ArticulationImpulse.hpp>
#include <coulomb/joints/tree/TreeDynamics.hpp>

#include "RandomTrees.hpp"

#include <stdexcept>

using namespace coulomb::joints::tree;
using randomtree::RandomSource;

namespace {
struct Case {
  Articulation tree;
  Eigen::VectorXd q;
  std::vector<PointImpulseRow> rows;
};

Case randomCase(unsigned seed, bool floating, int rowCount) {
  RandomSource random(seed);
  Articulation tree = randomtree::randomTree(random, {10, floating, true});
  Eigen::VectorXd q = randomtree::randomConfiguration(tree, random);
  const TreeKinematics kin = forwardKinematics(tree, q);
  std::vector<PointImpulseRow> rows;
  for (int r = 0; r < rowCount; ++r) {
    const int link = random.integer(0, tree.linkCount() - 1);
    rows.push_back({link, kin.worldPoses[link].apply(random.vector(0.4)), random.unitVector()});
  }
  return {std::move(tree), std::move(q), std::move(rows)};
}

double maxAbs(const Eigen::MatrixXd& m) {
  return m.lpNorm<Eigen::Infinity>();
}
}  // namespace

TEST(ArticulationImpulse, PointImpulseResponseIsInverseMassTimesJacobianTranspose) {
  for (unsigned seed = 1; seed <= 20; ++seed) {
    const Case c = randomCase(seed, seed % 2 == 0, 4);
    const ArticulationImpulse impulse(c.tree, c.q);
    const Eigen::MatrixXd mass = massMatrix(c.tree, c.q);
    const Eigen::LDLT<Eigen::MatrixXd> factor(mass);
    for (const PointImpulseRow& row : c.rows) {
      const Eigen::Vector3d p = 2.5 * row.direction;
      const Eigen::VectorXd expected = factor.solve(
          pointJacobian(c.tree, impulse.kinematics(), row.link, row.point).transpose() * p);
      const Eigen::VectorXd got = impulse.responseToPointImpulse(row.link, row.point, p);
      EXPECT_LE(maxAbs(got - expected), 1e-12 * std::max(1.0, maxAbs(expected))) << "seed " << seed;
    }
    RandomSource tauSource(seed);
    const Eigen::VectorXd tau = randomtree::randomVector(c.tree.nv(), tauSource, 1.0);
    const Eigen::VectorXd inverseMassTau = factor.solve(tau);
    EXPECT_LE(maxAbs(impulse.applyInverseMass(tau) - inverseMassTau),
              1e-12 * std::max(1.0, maxAbs(inverseMassTau)));
  }
}

TEST(ArticulationImpulse, DelassusIsJInverseMassJTransposeAndMatrixFreeAgrees) {
  for (unsigned seed = 30; seed <= 40; ++seed) {
    const Case c = randomCase(seed, seed % 2 == 0, 10);
    const ArticulationImpulse impulse(c.tree, c.q);
    const Eigen::MatrixXd jacobian = impulse.rowJacobian(c.rows);
    const Eigen::MatrixXd expected =
        jacobian * massMatrix(c.tree, c.q).ldlt().solve(jacobian.transpose());
    const Eigen::MatrixXd w = impulse.delassus(c.rows);
    const double scale = std::max(1.0, maxAbs(expected));
    EXPECT_LE(maxAbs(w - expected), 1e-12 * scale) << "seed " << seed;
    Eigen::VectorXd x(static_cast<Eigen::Index>(c.rows.size()));
    for (Eigen::Index r = 0; r < x.size(); ++r) x(r) = std::sin(1.0 + static_cast<double>(r));
    EXPECT_LE(maxAbs(impulse.applyDelassus(c.rows, x) - expected * x), 1e-12 * scale * x.size());
    EXPECT_LE(maxAbs(impulse.delassusColumn(c.rows, 3) - expected.col(3)), 1e-12 * scale);
    // Rows' velocities of a joint velocity are J qd.
    const Eigen::VectorXd qd = Eigen::VectorXd::LinSpaced(c.tree.nv(), -1.0, 1.0);
    EXPECT_LE(maxAbs(impulse.rowVelocities(c.rows, qd) - jacobian * qd), 1e-12);
  }
}

TEST(ArticulationImpulse, BadRowsAreClearErrors) {
  const Case c = randomCase(5, false, 2);
  const ArticulationImpulse impulse(c.tree, c.q);
  std::vector<PointImpulseRow> rows = c.rows;
  rows[1].link = c.tree.linkCount();
  EXPECT_THROW(impulse.delassus(rows), std::invalid_argument);
  rows = c.rows;
  rows[0].direction.x() = std::nan("");
  EXPECT_THROW(impulse.applyDelassus(rows, Eigen::VectorXd::Ones(2)), std::invalid_argument);
  EXPECT_THROW(impulse.applyDelassus(c.rows, Eigen::VectorXd::Ones(3)), std::invalid_argument);
}
