#include <gtest/gtest.h>
#include <coulomb/solvers/BodySpaceDelassus.hpp>
#include <coulomb/solvers/ContactProblem.hpp>

#include <limits>
#include <memory>

using namespace coulomb::solvers;

namespace {
ContactProblem twoContacts() {
  return ContactProblem::contacts(DelassusOperator::dense(Eigen::MatrixXd::Identity(6, 6)),
                                  Eigen::VectorXd::Constant(6, -1.0), {0.5, 0.3}, "two");
}
bool mentions(const std::optional<std::string>& m, const std::string& word) {
  return m && m->find(word) != std::string::npos;
}
}  // namespace

TEST(ContactProblem, WellFormedPasses) {
  const ContactProblem p = twoContacts();
  EXPECT_FALSE(p.validate().has_value());
  EXPECT_EQ(p.size(), 6);
  EXPECT_EQ(p.contactCount(), 2);
  EXPECT_EQ(p.blockOffsets().back(), 6);
}

TEST(ContactProblem, NamesTheFirstBrokenInvariant) {
  ContactProblem p = twoContacts();
  p.q.resize(5);
  EXPECT_TRUE(mentions(p.validate(), "q has 5"));
  p = twoContacts();
  p.W = DelassusOperator::dense(Eigen::MatrixXd::Identity(6, 5));
  EXPECT_TRUE(mentions(p.validate(), "not square"));
  p = twoContacts();
  p.blocks[1].mu = -0.1;
  EXPECT_TRUE(mentions(p.validate(), "mu = -0.1 < 0"));
  p = twoContacts();
  Eigen::MatrixXd W = Eigen::MatrixXd::Identity(6, 6);
  W(4, 1) = std::numeric_limits<double>::quiet_NaN();
  p.W = DelassusOperator::dense(W);
  EXPECT_TRUE(mentions(p.validate(), "W(4, 1) is not finite"));
  // The same in block-sparse storage (what the World's assembler gives every island).
  for (const double bad :
       {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()}) {
    p = twoContacts();
    W = Eigen::MatrixXd::Identity(6, 6);
    W(4, 1) = bad;
    auto sparse = std::make_shared<BlockSparseMatrix>();
    sparse->assignFromDense(W, {3, 3});
    p.W = DelassusOperator::blockSparse(sparse);
    EXPECT_TRUE(mentions(p.validate(), "W(4, 1) is not finite")) << bad;
  }
  p = twoContacts();
  W = Eigen::MatrixXd::Identity(6, 6);
  W(3, 3) = 0.0;
  p.W = DelassusOperator::dense(W);
  EXPECT_TRUE(mentions(p.validate(), "not positive on its diagonal"));
  p = twoContacts();
  p.q[2] = std::numeric_limits<double>::infinity();
  EXPECT_TRUE(mentions(p.validate(), "q at row 2"));
  p = twoContacts();
  p.warmStart = Eigen::VectorXd::Zero(3);
  EXPECT_TRUE(mentions(p.validate(), "warm start"));
  p = twoContacts();
  p.blocks.push_back(ConstraintBlock::bounded(1.0, -1.0));
  p.W = DelassusOperator::dense(Eigen::MatrixXd::Identity(7, 7));
  p.q = Eigen::VectorXd::Zero(7);
  EXPECT_TRUE(mentions(p.validate(), "not an interval"));
}

// Body-space W (the World's large islands): an inf or NaN anywhere in the factors J and
// M^-1 J^T, on a contact between two bodies or on one touching a static body, is named.
TEST(ContactProblem, NonFiniteBodySpaceFactorsAreNamed) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  for (const bool twoBodies : {true, false})
    for (const bool inJ : {true, false})
      for (const double bad : {nan, inf, -inf})
        for (int entry = 0; entry < 18; ++entry) {
          auto factors = std::make_shared<BodySpaceDelassus>(2, std::vector<int>{3});
          Eigen::Matrix<double, 3, 6, Eigen::RowMajor> J;
          J << 1, 0, 0, 0, 0.1, 0, 0, 1, 0, -0.1, 0, 0.2, 0, 0, 1, 0, -0.2, 0;
          Eigen::Matrix<double, 6, 3> G = J.transpose();
          (inJ ? J.data() : G.data())[entry] = bad;
          factors->setSide(0, 0, 0, J.data(), G.data());
          if (twoBodies) factors->setSide(0, 1, 1, J.data(), G.data());
          ContactProblem p = ContactProblem::contacts(DelassusOperator::bodySpace(factors),
                                                      Eigen::Vector3d(-1, 0, 0), {0.5}, "one");
          EXPECT_TRUE(mentions(p.validate(), "is not finite"))
              << twoBodies << inJ << bad << " at " << entry;
        }
}

TEST(ContactProblem, MixedBlocksAndMatrixFree) {
  ContactProblem p;
  p.blocks = {ConstraintBlock::equality(), ConstraintBlock::contact(0.2),
              ConstraintBlock::unilateral(), ConstraintBlock::anisotropicContact(0.1, 0.4)};
  EXPECT_EQ(p.size(), 8);
  p.q = Eigen::VectorXd::Zero(8);
  p.W = DelassusOperator::matrixFree(
      8, [](const Eigen::VectorXd& x, Eigen::VectorXd& y) { y = 2.0 * x; });
  EXPECT_FALSE(p.validate().has_value());
  p.blocks[3].mu2 = -1;
  EXPECT_TRUE(mentions(p.validate(), "mu2"));
}
