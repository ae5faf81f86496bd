#include <gtest/gtest.h>
#include <coulomb/solvers/io/Fc3dText.hpp>

#include <sstream>

#include "TestProblems.hpp"

using namespace coulomb::solvers;

TEST(Fc3dText, ReadsFixturesAndRoundTrips) {
  for (const char* name : fixtures::kFixtures) {
    const Fc3dReadResult r =
        readFc3dText(std::string(COULOMB_TEST_DATA_DIR) + "/fc3d/" + name + ".fc3d");
    ASSERT_TRUE(r.problem) << r.error;
    EXPECT_EQ(r.problem->name, name);
    EXPECT_FALSE(r.family.empty());
    std::stringstream s;
    EXPECT_EQ(writeFc3dText(*r.problem, s, r.family), "");
    const Fc3dReadResult back = parseFc3dText(s, "roundtrip");
    ASSERT_TRUE(back.problem) << back.error;
    EXPECT_EQ(back.problem->q, r.problem->q);  // bit-exact
    EXPECT_EQ(back.problem->W.blockSparseMatrix()->values(),
              r.problem->W.blockSparseMatrix()->values());
  }
}

TEST(Fc3dText, ErrorsNameFileLineAndWhat) {
  auto err = [](const std::string& text) {
    std::istringstream in(text);
    return parseFc3dText(in, "bad.fc3d").error;
  };
  EXPECT_EQ(
      err("fc3d-text 1\nname x\ncontacts 1\nmu 0.5\nq 1 2 3\nW 1\n0 0 1 0 0 0 1 0 0 0 1\nend\n"),
      "");
  EXPECT_NE(err("fc3d-txt 1").find("bad.fc3d:1: expected 'fc3d-text'"), std::string::npos);
  EXPECT_NE(err("fc3d-text 1\nname x\ncontacts 1\nmu -0.5\n").find("bad.fc3d:4: mu of contact 0"),
            std::string::npos);
  EXPECT_NE(err("fc3d-text 1\nname x\ncontacts 1\nmu 0.5\nq 1 2 abc\n").find("bad.fc3d:5"),
            std::string::npos);
  EXPECT_NE(err("fc3d-text 1\nname x\ncontacts 1\nmu 0.5\nq 1 2 3\nW 1\n0 1 1 0 0 0 1 0 0 0 1\nend")
                .find("contact index j"),
            std::string::npos);
  EXPECT_NE(err("fc3d-text 1\nname x\ncontacts 1\nmu 0.5\nq 1 2 3\nW 1\n0 0 1 0 0 0 1 0 0 0 1\n")
                .find("end of the file"),
            std::string::npos);
  EXPECT_NE(readFc3dText("/nonexistent/x.fc3d").error.find("cannot open"), std::string::npos);
}

TEST(Fc3dText, WriterRejectsNonContactBlocksAndWritesVectors) {
  ContactProblem p;
  p.blocks = {ConstraintBlock::equality()};
  p.W = DelassusOperator::dense(Eigen::MatrixXd::Identity(1, 1));
  p.q = Eigen::VectorXd::Zero(1);
  std::stringstream s;
  EXPECT_NE(writeFc3dText(p, s).find("equality"), std::string::npos);
  std::stringstream v;
  writeVector(Eigen::Vector3d(0.1, -2, 3e-300), v);
  EXPECT_EQ(v.str(), "0.1 -2 3e-300\n");
}
