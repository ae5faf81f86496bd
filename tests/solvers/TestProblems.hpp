#pragma once
// Small problems shared by the solver tests (header-only helpers, no tests here).
#include <coulomb/solvers/BodySpaceDelassus.hpp>
#include <coulomb/solvers/ContactProblem.hpp>
#include <coulomb/solvers/io/Fc3dText.hpp>

#include <Eigen/Dense>

#include <memory>
#include <random>
#include <string>

namespace coulomb::solvers::fixtures {

inline ContactProblem singleContact(const Eigen::Matrix3d& W, const Eigen::Vector3d& q, double mu) {
  return ContactProblem::contacts(DelassusOperator::dense(W), q, {mu}, "single");
}

// W = J M^-1 J^T and q = J v for `contacts` contacts and `dofs` degrees of freedom (random J, M).
// When 3 contacts <= dofs (nu <= 1) the normals also get a bias -1 (any q is in range(J)); with
// redundant contacts q stays in range(J), else the problem may have no solution (pitfall 12).
inline ContactProblem randomMechanical(int contacts, int dofs, double mu, unsigned seed,
                                       bool blockSparse = true) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> g(0.0, 1.0);
  const int n = 3 * contacts;
  Eigen::MatrixXd J(n, dofs);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < dofs; ++j) J(i, j) = g(rng);
  Eigen::MatrixXd L(dofs, dofs);
  for (int i = 0; i < dofs; ++i)
    for (int j = 0; j < dofs; ++j) L(i, j) = 0.3 * g(rng);
  const Eigen::MatrixXd Minv =
      (L * L.transpose() + Eigen::MatrixXd::Identity(dofs, dofs)).inverse();
  Eigen::VectorXd v(dofs);
  for (int j = 0; j < dofs; ++j) v[j] = g(rng);
  Eigen::MatrixXd W = J * Minv * J.transpose();
  W = 0.5 * (W + W.transpose());
  Eigen::VectorXd q = J * v;
  if (n <= dofs)
    for (int c = 0; c < contacts; ++c) q[3 * c] -= 1.0;  // mostly approaching contacts
  std::vector<double> mus(contacts, mu);
  DelassusOperator op = DelassusOperator::dense(W);
  if (blockSparse)
    op = DelassusOperator::blockSparse(op.toBlockSparse(std::vector<int>(contacts, 3)));
  return ContactProblem::contacts(op, q, mus, "random");
}

// A pile-like body-space problem: side x side bodies on a grid, `points` contacts between each
// body and its right and upper neighbours and between each body of the bottom row and the
// ground (static: no unknowns). Random J and SPD M^-1 per body; q = J v for a random v, so q is
// in range(J) and the problem has a solution.
inline ContactProblem bodyGrid(int side, int points, double mu, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> g(0.0, 1.0);
  const int bodies = side * side;
  std::vector<std::pair<int, int>> pairs;  // (lower body or -1, upper body)
  for (int i = 0; i < side; ++i)
    for (int j = 0; j < side; ++j) {
      const int b = i * side + j;
      for (int k = 0; k < points; ++k) {
        if (i == 0) pairs.emplace_back(-1, b);
        if (j + 1 < side) pairs.emplace_back(b, b + 1);
        if (i + 1 < side) pairs.emplace_back(b, b + side);
      }
    }
  const int contacts = static_cast<int>(pairs.size());
  std::vector<Eigen::Matrix<double, 6, 6>> Minv(bodies);
  for (auto& m : Minv) {
    Eigen::Matrix<double, 6, 6> L;
    for (int a = 0; a < 6; ++a)
      for (int c = 0; c < 6; ++c) L(a, c) = 0.3 * g(rng);
    m = (L * L.transpose() + Eigen::Matrix<double, 6, 6>::Identity()).inverse();
  }
  Eigen::VectorXd v(6 * bodies);
  for (int k = 0; k < v.size(); ++k) v[k] = g(rng);
  auto factors = std::make_shared<BodySpaceDelassus>(bodies, std::vector<int>(contacts, 3));
  Eigen::VectorXd q = Eigen::VectorXd::Zero(3 * contacts);
  for (int c = 0; c < contacts; ++c)
    for (const auto& [s, body] : {std::pair{0, pairs[c].first}, std::pair{1, pairs[c].second}}) {
      if (body < 0) continue;
      Eigen::Matrix<double, 3, 6> J;
      for (int a = 0; a < 3; ++a)
        for (int k = 0; k < 6; ++k) J(a, k) = g(rng);
      const Eigen::Matrix<double, 6, 3> G = Minv[body] * J.transpose();
      factors->setSide(c, s, body, J, G);
      q.segment<3>(3 * c) += J * v.segment<6>(6 * body);
    }
  return ContactProblem::contacts(DelassusOperator::bodySpace(factors), q,
                                  std::vector<double>(contacts, mu), "grid");
}

inline ContactProblem loadFixture(const std::string& name) {
  Fc3dReadResult r = readFc3dText(std::string(COULOMB_TEST_DATA_DIR) + "/fc3d/" + name + ".fc3d");
  if (!r.problem) throw std::runtime_error(r.error);
  return *r.problem;
}

// A problem captured from one of the engine's scenes (tests/data/problems/ORIGIN.md).
inline ContactProblem loadCapturedProblem(const std::string& name) {
  Fc3dReadResult r =
      readFc3dText(std::string(COULOMB_TEST_DATA_DIR) + "/problems/" + name + ".fc3d");
  if (!r.problem) throw std::runtime_error(r.error);
  return *r.problem;
}

inline const char* const kFixtures[] = {"FrictionContact3D_1c",
                                        "FC3D_Example1",
                                        "GFC3D_Example00_badly_scaled",
                                        "Confeti-ex13-4contact-Fc3D-SBM",
                                        "Rover1039",
                                        "GFC3D_TwoRods1-condensed",
                                        "OneObject-i1028-138"};

}  // namespace coulomb::solvers::fixtures
