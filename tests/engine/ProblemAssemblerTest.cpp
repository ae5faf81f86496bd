#include <gtest/gtest.h>
#include <coulomb/engine/ImpulseApplier.hpp>
#include <coulomb/engine/ProblemAssembler.hpp>
#include <coulomb/joints/ContactRows.hpp>
#include <coulomb/solvers/BodySpaceDelassus.hpp>

#include <Eigen/Geometry>

using namespace coulomb;
using geometry::BodyId;
using geometry::MotionType;

namespace {

// Three bodies: 0 static ground, 1 and 2 dynamic boxes (different masses, rotated inertias).
geometry::BodyState threeBodies() {
  geometry::BodyState state;
  const Eigen::Matrix3d unit = Eigen::Matrix3d::Identity();
  state.assign(0, MotionType::Static, geometry::Pose{}, Eigen::Vector3d::Zero(),
               Eigen::Vector3d::Zero(), 0.0, unit);
  geometry::Pose p1 = geometry::Pose::translation(Eigen::Vector3d(0, 0, 0.5));
  p1.rotation = Eigen::AngleAxisd(0.3, Eigen::Vector3d(1, 2, 3).normalized());
  state.assign(1, MotionType::Dynamic, p1, Eigen::Vector3d(0.1, 0, -1), Eigen::Vector3d(0, 0.2, 0),
               2.0, Eigen::Vector3d(0.3, 0.4, 0.5).asDiagonal());
  state.assign(2, MotionType::Dynamic, geometry::Pose::translation(Eigen::Vector3d(0, 0, 1.5)),
               Eigen::Vector3d(0, 0, -2), Eigen::Vector3d::Zero(), 5.0,
               Eigen::Vector3d(1.0, 1.0, 2.0).asDiagonal());
  for (std::size_t i = 0; i < state.size(); ++i) state.refreshWorldInertia(i);
  return state;
}

// The rows of a contact between bodies a and b at `point` (normal +z) with friction mu.
joints::RowBlock contactRows(const geometry::BodyState& state, std::uint32_t a, std::uint32_t b,
                             const Eigen::Vector3d& point, double mu) {
  joints::ContactPointFrame c;
  c.bodyA = BodyId{a, 0};
  c.bodyB = BodyId{b, 0};
  c.point = point;
  c.centreA = state.poses[a].position;
  c.centreB = state.poses[b].position;
  c.friction = mu;
  return joints::makeContactRows(c);
}

joints::RowSet stackRows(const geometry::BodyState& state) {
  joints::RowSet rows;
  auto add = [&](std::uint32_t a, std::uint32_t b, const Eigen::Vector3d& point, double mu) {
    rows.blocks.push_back(contactRows(state, a, b, point, mu));
  };
  add(0, 1, Eigen::Vector3d(0.4, 0.3, 0.0), 0.5);
  add(0, 1, Eigen::Vector3d(-0.4, 0.3, 0.0), 0.0);  // frictionless: one unilateral row
  add(1, 2, Eigen::Vector3d(0.2, -0.1, 1.0), 0.8);
  return rows;
}

// Reference: the global J (rows x 18) and M^-1 (18 x 18) multiplied out.
Eigen::MatrixXd bruteForceW(const joints::RowSet& rows, const geometry::BodyState& state) {
  const int n = rows.rowCount();
  Eigen::MatrixXd J = Eigen::MatrixXd::Zero(n, 18), Minv = Eigen::MatrixXd::Zero(18, 18);
  int r = 0;
  for (const auto& b : rows.blocks) {
    J.block(r, 6 * b.bodyA.index, b.rows(), 6) += b.jacobianA;
    J.block(r, 6 * b.bodyB.index, b.rows(), 6) += b.jacobianB;
    r += b.rows();
  }
  for (std::uint32_t i = 0; i < 3; ++i) {
    if (!state.isDynamic(i)) continue;
    Minv.block<3, 3>(6 * i, 6 * i) = state.inverseMasses[i] * Eigen::Matrix3d::Identity();
    Minv.block<3, 3>(6 * i + 3, 6 * i + 3) = state.worldInverseInertias[i];
  }
  return J * Minv * J.transpose();
}

}  // namespace

TEST(ProblemAssembler, SparseAndFactoredDelassusMatchTheGlobalProduct) {
  const auto state = threeBodies();
  const auto rows = stackRows(state);
  const Eigen::MatrixXd reference = bruteForceW(rows, state);

  // Small islands: W's entries, block-sparse (also above the limit with bodySpace off).
  const auto small = engine::ProblemAssembler().assemble(rows, state);
  const auto sparse =
      engine::ProblemAssembler({.sparseRowLimit = 0, .bodySpace = false}).assemble(rows, state);
  const auto factored = engine::ProblemAssembler({.sparseRowLimit = 0}).assemble(rows, state);
  ASSERT_EQ(small.problem.W.storage(), solvers::DelassusOperator::Storage::BlockSparse);
  ASSERT_EQ(sparse.problem.W.storage(), solvers::DelassusOperator::Storage::BlockSparse);
  ASSERT_EQ(factored.problem.W.storage(), solvers::DelassusOperator::Storage::BodySpace);
  EXPECT_LT((small.problem.W.blockSparseMatrix()->toDense() - reference).norm(), 1e-13);
  EXPECT_LT((sparse.problem.W.blockSparseMatrix()->toDense() - reference).norm(), 1e-13);
  const auto sizes = factored.problem.blockSizes();
  EXPECT_LT((factored.problem.W.toBlockSparse(sizes).toDense() - reference).norm(), 1e-13);
  // W x through the body velocities equals the product with the entries.
  const Eigen::VectorXd x = Eigen::VectorXd::LinSpaced(reference.rows(), -1.0, 2.0);
  Eigen::VectorXd u;
  factored.problem.W.velocity(x, Eigen::VectorXd::Zero(x.size()), u);
  EXPECT_LT((u - reference * x).norm(), 1e-13);
  small.problem.W.velocity(x, Eigen::VectorXd::Zero(x.size()), u);
  EXPECT_LT((u - reference * x).norm(), 1e-13);
  EXPECT_FALSE(small.problem.validate().has_value());
  EXPECT_FALSE(sparse.problem.validate().has_value());
  EXPECT_FALSE(factored.problem.validate().has_value());
  EXPECT_EQ(small.problem.size(), 7);
  EXPECT_EQ(small.problem.contactCount(), 2);
  EXPECT_EQ(small.degreesOfFreedom, 12);  // the static ground carries no unknowns
}

TEST(ProblemAssembler, ContactIslandsGetAnExactlySymmetricW) {
  // Contact blocks only (the 3 x 3 path): two contacts between the same two boxes, one on the
  // ground, and one between the ground and the top box (no shared body with the first).
  const auto state = threeBodies();
  joints::RowSet rows;
  auto add = [&](std::uint32_t a, std::uint32_t b, const Eigen::Vector3d& point, double mu) {
    rows.blocks.push_back(contactRows(state, a, b, point, mu));
  };
  add(0, 1, Eigen::Vector3d(0.4, 0.3, 0.0), 0.5);
  add(1, 2, Eigen::Vector3d(0.2, -0.1, 1.0), 0.8);
  add(1, 2, Eigen::Vector3d(-0.3, 0.2, 1.0), 0.8);
  add(0, 2, Eigen::Vector3d(1.0, 1.0, 0.0), 0.3);
  const auto assembled = engine::ProblemAssembler().assemble(rows, state);
  const solvers::BlockSparseMatrix* W = assembled.problem.W.blockSparseMatrix();
  ASSERT_NE(W, nullptr);
  const Eigen::MatrixXd dense = W->toDense();
  EXPECT_LT((dense - bruteForceW(rows, state)).norm(), 1e-13);
  EXPECT_TRUE((dense.array() == dense.transpose().array()).all());  // bit for bit
  // Blocks (0, 3) share no dynamic body (the ground carries none): not stored.
  EXPECT_EQ(W->nonZeroBlocks(), 16 - 2);
  EXPECT_FALSE(assembled.problem.validate().has_value());
}

TEST(ProblemAssembler, FreeVelocityIsJTimesTheTwists) {
  const auto state = threeBodies();
  const auto rows = stackRows(state);
  const auto assembled = engine::ProblemAssembler().assemble(rows, state);
  // Normal of the last contact: n . (v_2(p) - v_1(p)) with v_i(p) = v_i + w_i x (p - c_i).
  const Eigen::Vector3d p(0.2, -0.1, 1.0);
  const Eigen::Vector3d v1 =
      state.linearVelocities[1] + state.angularVelocities[1].cross(p - state.poses[1].position);
  const Eigen::Vector3d v2 = state.linearVelocities[2];
  EXPECT_NEAR(assembled.problem.q[4], (v2 - v1).z(), 1e-15);
}

TEST(ProblemAssembler, AppliedImpulseChangesVelocityByWTimesLambda) {
  auto state = threeBodies();
  const auto rows = stackRows(state);
  const auto assembled = engine::ProblemAssembler().assemble(rows, state);
  Eigen::VectorXd lambda(7);
  lambda << 1.0, 0.2, -0.1, 0.5, 0.7, 0.05, 0.3;
  engine::applyImpulses(rows, assembled.slots, lambda, state);
  const auto after = engine::ProblemAssembler().assemble(rows, state);
  // u+ = q + W lambda: the post-impulse constraint velocities.
  Eigen::VectorXd expected;
  assembled.problem.W.velocity(lambda, assembled.problem.q, expected);
  EXPECT_LT((after.problem.q - expected).norm(), 1e-13);
  EXPECT_EQ(state.linearVelocities[0], Eigen::Vector3d::Zero());  // static never moves
}

// One warm-started block makes the island's warm start; a block without one (a contact new this
// step) starts at zero within it, the others keep theirs. No block with one: no warm start.
TEST(ProblemAssembler, WarmStartFromAnyBlockWithNewBlocksAtZero) {
  const auto state = threeBodies();
  auto rows = stackRows(state);
  EXPECT_FALSE(engine::ProblemAssembler().assemble(rows, state).problem.warmStart.has_value());
  for (auto& b : rows.blocks) b.warmStart = joints::RowVector::Constant(b.rows(), 0.25);
  const auto assembled = engine::ProblemAssembler().assemble(rows, state);
  ASSERT_TRUE(assembled.problem.warmStart.has_value());
  EXPECT_DOUBLE_EQ((*assembled.problem.warmStart)[6], 0.25);

  ASSERT_GE(rows.blocks.size(), 2u);
  rows.blocks.front().warmStart.resize(0);  // the first block is new
  const auto partly = engine::ProblemAssembler().assemble(rows, state);
  ASSERT_TRUE(partly.problem.warmStart.has_value());
  const Eigen::VectorXd& warm = *partly.problem.warmStart;
  ASSERT_EQ(warm.size(), partly.problem.q.size());
  const int firstRows = partly.slots[0].rows;
  EXPECT_EQ(warm.segment(partly.slots[0].offset, firstRows).cwiseAbs().maxCoeff(), 0.0);
  for (std::size_t k = 1; k < rows.blocks.size(); ++k)
    EXPECT_EQ(warm.segment(partly.slots[k].offset, partly.slots[k].rows).minCoeff(), 0.25)
        << "block " << k;
}

// The rows' velocities at the step's start, formed when a solve asks (arrivalRowVelocities): J v_k
// of the bodies that carry unknowns, as a body-space W forms them from the bodies' v_k.
TEST(ProblemAssembler, ArrivalRowsAreJTimesTheArrivalTwists) {
  auto state = threeBodies();
  const auto rows = stackRows(state);
  std::vector<Eigen::Vector3d> linear = {Eigen::Vector3d(5, 5, 5), Eigen::Vector3d(0.3, -0.2, 0.1),
                                         Eigen::Vector3d(-0.1, 0.4, 0.2)};
  std::vector<Eigen::Vector3d> angular = {Eigen::Vector3d(1, 1, 1), Eigen::Vector3d(0.5, 0.1, -0.3),
                                          Eigen::Vector3d(0.2, -0.6, 0.7)};
  const engine::ArrivalVelocities arrival{linear, angular};
  Eigen::VectorXd expected = Eigen::VectorXd::Zero(rows.rowCount());
  int r = 0;
  for (const auto& b : rows.blocks) {
    for (const bool sideB : {false, true}) {
      const std::uint32_t body = (sideB ? b.bodyB : b.bodyA).index;
      if (!state.isDynamic(body)) continue;  // the ground's v_k is not the rows' (5, 5, 5)
      Eigen::Matrix<double, 6, 1> twist;
      twist << linear[body], angular[body];
      expected.segment(r, b.rows()) += (sideB ? b.jacobianB : b.jacobianA) * twist;
    }
    r += b.rows();
  }
  engine::AssembledProblem small;
  engine::ProblemAssembler().assemble(rows, state, nullptr, nullptr, small, &arrival);
  Eigen::VectorXd formed;
  engine::arrivalRowVelocities(rows, state, arrival, small.slots, formed);
  ASSERT_EQ(formed.size(), expected.size());
  EXPECT_LT((formed - expected).norm(), 1e-14);

  // The body-space W's own: J (v_k of its bodies), from ContactProblem::arrival.
  engine::AssembledProblem factored;
  engine::ProblemAssembler({.sparseRowLimit = 0})
      .assemble(rows, state, nullptr, nullptr, factored, &arrival);
  const solvers::BodySpaceDelassus* factors = factored.problem.W.bodySpaceOperator();
  ASSERT_NE(factors, nullptr);
  ASSERT_EQ(factored.problem.arrival.size(), 12);  // two bodies with unknowns
  Eigen::VectorXd fromFactors = Eigen::VectorXd::Zero(expected.size());
  factors->addRowVelocities(factored.problem.arrival, fromFactors.data());
  EXPECT_LT((fromFactors - expected).norm(), 1e-14);
}

// With the default settings an island of up to 16 contacts (48 rows: two stacked boxes, four
// points per face, with room to spare) gets W's entries, and one of 20 contacts (60 rows: a column
// of five boxes) keeps W's factors, so that its Newton steps can be solved in body space
// (docs/benchmarks.md "Columns in body space"). Under the former 96-row limit both had entries.
TEST(ProblemAssembler, ColumnsOfMoreThanSixteenContactsKeepWFactored) {
  const geometry::BodyState state = threeBodies();
  auto faces = [&](int count) {
    joints::RowSet rows;
    for (int k = 0; k < count; ++k) {
      const double x = (k % 2 == 0 ? 0.1 : -0.1), y = ((k / 2) % 2 == 0 ? 0.1 : -0.1);
      const std::uint32_t below = k < count / 2 ? 0 : 1, above = k < count / 2 ? 1 : 2;
      rows.blocks.push_back(contactRows(state, below, above, Eigen::Vector3d(x, y, 0.2 * k), 0.5));
    }
    return rows;
  };
  const engine::AssembledProblem small = engine::ProblemAssembler().assemble(faces(16), state);
  EXPECT_NE(small.problem.W.blockSparseMatrix(), nullptr);
  EXPECT_EQ(small.problem.W.bodySpaceOperator(), nullptr);
  const engine::AssembledProblem column = engine::ProblemAssembler().assemble(faces(20), state);
  EXPECT_NE(column.problem.W.bodySpaceOperator(), nullptr);
}
