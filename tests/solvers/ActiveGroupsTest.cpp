// Islands solved by their groups of acting contacts (solvers/ActiveGroups.hpp, docs/solvers.md
// "Islands by their groups of acting contacts"), on point masses of 1 kg (translation only) whose
// contacts have axis-aligned frames, so that W = J M^-1 J^T and the answers are known exactly.
#include <gtest/gtest.h>
#include <coulomb/solvers/ActiveGroups.hpp>
#include <coulomb/solvers/Residual.hpp>
#include <coulomb/solvers/SolverRegistry.hpp>

#include <array>
#include <vector>

using namespace coulomb::solvers;

namespace {

struct PointContact {
  int below, above;  // body indices; -1: the ground
  int axis;          // the normal, from `below` to `above`: 0 x, 1 y, 2 z
  double gap;        // [m]; a positive gap lets the contact close by gap / h in the step
};

constexpr double kStep = 0.01;

// Rows (n, t1, t2) of a contact whose normal is `axis`.
Eigen::Matrix3d frame(int axis) {
  Eigen::Matrix3d R = Eigen::Matrix3d::Zero();
  for (int k = 0; k < 3; ++k) R(k, (axis + k) % 3) = 1.0;
  return R;
}

// W = J J^T and q = J v* + (gap / h) e_N for unit point masses with velocities v* (3 per body).
ContactProblem pointProblem(const std::vector<PointContact>& contacts,
                            const std::vector<Eigen::Vector3d>& velocities, double mu) {
  const int n = static_cast<int>(contacts.size());
  std::vector<int> rowStart{0}, columns;
  std::vector<double> values;
  Eigen::VectorXd q(3 * n);
  for (int i = 0; i < n; ++i) {
    const PointContact& a = contacts[i];
    for (int j = 0; j < n; ++j) {
      const PointContact& b = contacts[j];
      Eigen::Matrix3d block = Eigen::Matrix3d::Zero();
      for (const int body : {a.below, a.above}) {
        if (body < 0) continue;
        const double si = body == a.above ? 1.0 : -1.0;
        for (const int other : {b.below, b.above})
          if (other == body)
            block +=
                si * (other == b.above ? 1.0 : -1.0) * frame(a.axis) * frame(b.axis).transpose();
      }
      if (i != j && block.isZero()) continue;
      columns.push_back(j);
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) values.push_back(block(r, c));
    }
    rowStart.push_back(static_cast<int>(columns.size()));
    Eigen::Vector3d relative = Eigen::Vector3d::Zero();
    if (a.above >= 0) relative += velocities[a.above];
    if (a.below >= 0) relative -= velocities[a.below];
    q.segment<3>(3 * i) = frame(a.axis) * relative;
    q[3 * i] += a.gap / kStep;
  }
  return ContactProblem::contacts(
      DelassusOperator::blockSparse(BlockSparseMatrix::fromBlockCsr(
          std::vector<int>(n, 3), std::move(rowStart), std::move(columns), std::move(values))),
      q, std::vector<double>(n, mu), "points");
}

SolverOptions tight() {
  SolverOptions o;
  o.tolerance = 1e-10;
  return o;
}

std::optional<PlanOutcome> solveByGroups(const ContactProblem& p) {
  return solveByActiveGroups(p, SolverChooser(), SolverChoice{}, tight(),
                             SolverRegistry::builtIn());
}

}  // namespace

// Two bodies falling onto the ground side by side (two points each), 1 cm apart with a
// speculative contact between them that r = 0 keeps (q_N = gap / h > 0): one island, two groups.
// Each body is stopped by its own points (m g h between them), the left-out contact stays open, and
// the answer is the whole problem's.
TEST(ActiveGroups, SideBySideBodiesAreSolvedAsTwoGroups) {
  const double fall = -9.81 * kStep;
  const ContactProblem p = pointProblem(
      {{-1, 0, 2, 0.0}, {-1, 0, 2, 0.0}, {-1, 1, 2, 0.0}, {-1, 1, 2, 0.0}, {0, 1, 0, 0.01}},
      {Eigen::Vector3d(0, 0, fall), Eigen::Vector3d(0, 0, fall)}, 0.5);
  UnionFind scratch;
  ASSERT_TRUE(splitsByActingContacts(p, scratch));
  const std::optional<PlanOutcome> out = solveByGroups(p);
  ASSERT_TRUE(out.has_value());
  EXPECT_EQ(out->status, SolverStatus::Converged);
  EXPECT_EQ(out->best.report.solver, "groups");
  EXPECT_NE(out->best.report.message.find("2 groups"), std::string::npos)
      << out->best.report.message;
  EXPECT_NE(out->best.report.message.find("1 rounds"), std::string::npos)
      << out->best.report.message;
  const Eigen::VectorXd& r = out->best.impulses;
  EXPECT_NEAR(r[0] + r[3], -fall, 1e-9);
  EXPECT_NEAR(r[6] + r[9], -fall, 1e-9);
  EXPECT_EQ(r.segment<3>(12).norm(), 0.0);  // the gap between the bodies stays open
  EXPECT_LE(commonResidual(p, r).relative, 1e-10);
}

// A body falling onto another that the ground stops: their contact (a 0.5 mm gap, which the
// common fall does not close: q_N = gap / h > 0) is left out at first, but once the lower body is
// stopped the upper one approaches it at 9.81 h - gap / h, so it joins the lower body's group in a
// second round. A third body elsewhere keeps the island split. The upper body's momentum then
// reaches the ground through the lower one: 2 m g h on the lower body's points, m g h between them.
TEST(ActiveGroups, AContactTheGroupsDriveIntoApproachJoinsInTheNextRound) {
  const double fall = -9.81 * kStep;
  const ContactProblem p = pointProblem(
      {{-1, 0, 2, 0.0}, {-1, 0, 2, 0.0}, {0, 1, 2, 0.0005}, {-1, 2, 2, 0.0}},
      {Eigen::Vector3d(0, 0, fall), Eigen::Vector3d(0, 0, fall), Eigen::Vector3d(0, 0, fall)}, 0.5);
  const std::optional<PlanOutcome> out = solveByGroups(p);
  ASSERT_TRUE(out.has_value());
  EXPECT_NE(out->best.report.message.find("2 rounds"), std::string::npos)
      << out->best.report.message;
  const Eigen::VectorXd& r = out->best.impulses;
  EXPECT_NEAR(r[0] + r[3], -2 * fall - 0.0005 / kStep, 1e-9);  // the upper body lands in the gap
  EXPECT_NEAR(r[6], -fall - 0.0005 / kStep, 1e-9);
  EXPECT_NEAR(r[9], -fall, 1e-9);
  EXPECT_LE(commonResidual(p, r).relative, 1e-10);
}

// Contacts that all act (a resting stack) or a single acting group: nothing to split, and the
// caller runs its whole plan.
TEST(ActiveGroups, OneGroupIsLeftToTheWholePlan) {
  const double fall = -9.81 * kStep;
  const ContactProblem p =
      pointProblem({{-1, 0, 2, 0.0}, {-1, 0, 2, 0.0}, {0, 1, 2, 0.0}},
                   {Eigen::Vector3d(0, 0, fall), Eigen::Vector3d(0, 0, fall)}, 0.5);
  UnionFind scratch;
  EXPECT_FALSE(splitsByActingContacts(p, scratch));
  EXPECT_FALSE(solveByGroups(p).has_value());
}
