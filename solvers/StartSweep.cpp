#include <coulomb/solvers/StartSweep.hpp>

#include <coulomb/solvers/CoulombLaw.hpp>
#include <coulomb/solvers/GaussSeidelLoop.hpp>
#include <coulomb/solvers/bgs/LocalContactSolver.hpp>

#include <Eigen/Cholesky>

#include <cmath>
#include <optional>

namespace coulomb::solvers {

namespace {

// Sliding (docs/solver-derivations.md (4.5)) found from a known direction: r = r_N (1, mu s),
// s = (cos th, sin th) the tangential impulse's direction; u_N = 0 gives
// r_N = -q_N / (W_NN + mu W_NT s), and the law asks u_T = r_N (W_TN + mu W_TT s) + q_T to be
// antiparallel to s: g(th) = p . u_T = 0 with p = ds/dth, and s . u_T < 0. Newton on th from the
// start's direction (a sliding contact's warm start is within a few degrees of it): two or three
// steps of a dozen flops each, where the general local solver (an angle scan, a 3 x 3 Newton with
// a line search) costs two thousand instructions. Empty when the iteration does not settle on
// a slip answer (sliding slowly, a start far off): the general solver then decides.
std::optional<Eigen::Vector3d> slideFrom(const Eigen::Matrix3d& W, const Eigen::Vector3d& q,
                                         double mu, Eigen::Vector2d s) {
  const Eigen::Vector2d wNT(W(0, 1), W(0, 2)), wTN(W(1, 0), W(2, 0));
  const Eigen::Matrix2d wTT = W.bottomRightCorner<2, 2>();
  const Eigen::Vector2d qT = q.tail<2>();
  constexpr int kMaxSteps = 8;
  constexpr double kSettled = 1e-13;  // [rad]: the next step is at rounding (quadratic)
  for (int step = 0; step <= kMaxSteps; ++step) {
    const Eigen::Vector2d p(-s[1], s[0]);
    const double den = W(0, 0) + mu * wNT.dot(s);
    if (!(den > 0.0)) return std::nullopt;
    const double rN = -q[0] / den;
    const Eigen::Vector2d v = wTN + mu * (wTT * s);
    const Eigen::Vector2d uT = rN * v + qT;
    const double g = p.dot(uT), along = s.dot(uT);
    if (!(rN > 0.0) || !(along < 0.0)) return std::nullopt;
    const double drN = -rN * mu * wNT.dot(p) / den;
    const double dg = -along + p.dot(drN * v + rN * mu * (wTT * p));
    const double delta = -g / dg;
    if (!std::isfinite(delta)) return std::nullopt;
    if (std::abs(delta) <= kSettled) return Eigen::Vector3d(rN, mu * rN * s[0], mu * rN * s[1]);
    s = (s + delta * p).normalized();  // the angle th + atan(delta): still a Newton step
  }
  return std::nullopt;
}

// The direction to start sliding from: the incoming impulse's when it has one, else the
// isotropic answer's (4.4), against q_T.
std::optional<Eigen::Vector2d> slideStart(const Eigen::Vector3d& incoming,
                                          const Eigen::Vector3d& q) {
  const double incomingT = tangentNorm(incoming[1], incoming[2]);
  if (incoming[0] > 0.0 && incomingT > 0.0)
    return Eigen::Vector2d(incoming[1], incoming[2]) / incomingT;
  const double qT = tangentNorm(q[1], q[2]);
  if (qT > 0.0) return Eigen::Vector2d(-q[1], -q[2]) / qT;
  return std::nullopt;
}

}  // namespace

bool sweepContacts(const PreparedProblem& problem, Eigen::VectorXd& r) {
  if (problem.bodySpace) return false;
  const BlockSparseMatrix& W = problem.W();
  for (int b = 0; b < problem.blockCount(); ++b) {
    if (!problem.blocks[b].isContact()) continue;
    const int o = problem.offset[b];
    // q~ = q_b + sum over j != b of W_bj r_j: the contact's problem with the others held.
    const int diagonal = W.diagonalBlock(b);
    if (diagonal < 0) continue;  // not a valid problem (validate() names it)
    Eigen::Vector3d qt;
    localFreeVelocity(problem, b, r, qt.data());
    const double mu = problem.blocks[b].mu;
    if (qt[0] >= 0.0) {  // take-off: r = 0 leaves u = q~ in the dual cone
      r.segment<3>(o).setZero();
      continue;
    }
    const Eigen::Matrix3d Wbb =
        Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(W.blockValues(diagonal));
    // Sticking (u = 0) when that answer lies in the cone: the closed form of (4.1) without the
    // local solver's set-up (its LU and spectral radii), the common case of a resting island.
    const Eigen::Vector3d stick = -Wbb.ldlt().solve(qt);
    if (stick.allFinite() && stick[0] > 0.0 && tangentNorm(stick[1], stick[2]) <= mu * stick[0]) {
      r.segment<3>(o) = stick;
      continue;
    }
    const Eigen::Vector3d incoming = r.segment<3>(o);
    if (const auto direction = slideStart(incoming, qt)) {
      if (const auto slide = slideFrom(Wbb, qt, mu, *direction)) {
        r.segment<3>(o) = *slide;
        continue;
      }
    }
    r.segment<3>(o) = solveLocalContact(LocalContactData::from(Wbb), qt, mu, incoming).r;
  }
  return true;
}

}  // namespace coulomb::solvers
