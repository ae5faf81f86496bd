#include <coulomb/solvers/lemke/LemkeSolver.hpp>

#include <Eigen/LU>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <vector>

namespace coulomb::solvers {

namespace {

constexpr double kPi = 3.14159265358979323846;

bool isFree(const ConstraintBlock& b) {
  return b.kind == BlockKind::Equality ||
         (b.kind == BlockKind::Bounded && std::isinf(b.lower) && std::isinf(b.upper));
}

// LCP variables per block: contact n_d + 2, box 2, one-sided 1, free 0 (eliminated).
int lcpVariables(const ConstraintBlock& b, int nd) {
  if (isFree(b)) return 0;
  if (b.isContact()) return nd + 2;
  if (b.kind == BlockKind::Bounded && std::isfinite(b.lower) && std::isfinite(b.upper)) return 2;
  return 1;
}

// The LCP of the non-free rows c after eliminating the free rows f (7.5):
//   r_c = S z + g0,  u_c = W~ r_c + q~,  w = S^T u_c + (lambda, box columns) ...
struct FacetedLcp {
  Eigen::MatrixXd M;
  Eigen::VectorXd b;
  Eigen::MatrixXd S;    // |c| x lcp: r_c = S z + g0
  Eigen::VectorXd g0;   // offsets of bounded rows
  std::vector<int> c;   // original indices of the kept rows
  std::vector<int> f;   // original indices of the eliminated rows
  Eigen::MatrixXd Wff;  // regularized, for the recovery of r_f
  Eigen::MatrixXd Wfc;
  Eigen::VectorXd qf;
};

FacetedLcp buildLcp(const PreparedProblem& p, const LemkeOptions& o) {
  FacetedLcp L;
  const int nd = o.frictionDirections;
  const Eigen::MatrixXd W = p.W().toDense();
  int lcpSize = 0;
  for (int blk = 0; blk < p.blockCount(); ++blk) {
    const ConstraintBlock& b = p.blocks[blk];
    for (int a = 0; a < b.size(); ++a) (isFree(b) ? L.f : L.c).push_back(p.offset[blk] + a);
    lcpSize += lcpVariables(b, nd);
  }
  const int nc = static_cast<int>(L.c.size()), nf = static_cast<int>(L.f.size());
  Eigen::MatrixXd Wt(nc, nc);
  Eigen::VectorXd qt(nc);
  for (int i = 0; i < nc; ++i) {
    qt[i] = p.q[L.c[i]];
    for (int j = 0; j < nc; ++j) Wt(i, j) = W(L.c[i], L.c[j]);
  }
  if (nf > 0) {  // Schur complement (7.5)
    L.Wff.resize(nf, nf);
    L.Wfc.resize(nf, nc);
    Eigen::MatrixXd Wcf(nc, nf);
    L.qf.resize(nf);
    double maxDiag = 0;
    for (int i = 0; i < nf; ++i) {
      L.qf[i] = p.q[L.f[i]];
      for (int j = 0; j < nf; ++j) L.Wff(i, j) = W(L.f[i], L.f[j]);
      for (int j = 0; j < nc; ++j) L.Wfc(i, j) = W(L.f[i], L.c[j]), Wcf(j, i) = W(L.c[j], L.f[i]);
      maxDiag = std::max(maxDiag, L.Wff(i, i));
    }
    L.Wff.diagonal().array() += o.equalityRegularization * maxDiag;
    if (nc > 0) {  // Eigen's triangular solve reads entry (0, 0) of an empty right-hand side
      const Eigen::PartialPivLU<Eigen::MatrixXd> lu(L.Wff);
      Wt -= Wcf * lu.solve(L.Wfc);
      qt -= Wcf * lu.solve(L.qf);
    }
  }
  // Scaled by s = max diag W~ (u / s = (W~ / s) r + q~ / s has the same r): the tableau's entries
  // are then O(1) next to the unit entries of the slack rows whatever the units of W, so that the
  // pivot tolerance relative to max|M| means the same on every problem. The slack lambda and the
  // box variable z2 become lambda / s and z2 / s; neither is part of r.
  double scale = nc > 0 ? Wt.diagonal().cwiseAbs().maxCoeff() : 1.0;
  if (!(scale > 0) || !std::isfinite(scale)) scale = 1.0;
  Wt /= scale;
  qt /= scale;
  // S, g0 and the extra entries (lambda rows/columns, box columns) per block, in block order.
  L.S = Eigen::MatrixXd::Zero(nc, lcpSize);
  L.g0 = Eigen::VectorXd::Zero(nc);
  Eigen::MatrixXd extra = Eigen::MatrixXd::Zero(lcpSize, lcpSize);
  Eigen::VectorXd extraB = Eigen::VectorXd::Zero(lcpSize);
  std::vector<bool> primary(lcpSize, false);  // rows w = S^T u + ...
  int row = 0, v = 0;                         // row of c, LCP variable
  for (int blk = 0; blk < p.blockCount(); ++blk) {
    const ConstraintBlock& b = p.blocks[blk];
    if (isFree(b)) continue;
    if (b.isContact()) {  // (7.1)-(7.3): (r_N, beta_1..nd, lambda)
      L.S(row, v) = 1.0;
      primary[v] = true;
      for (int k = 0; k < nd; ++k) {
        const double th = 2.0 * kPi * k / nd;
        L.S(row + 1, v + 1 + k) = std::cos(th);
        L.S(row + 2, v + 1 + k) = std::sin(th);
        primary[v + 1 + k] = true;
        extra(v + 1 + k, v + nd + 1) = 1.0;   // E: + lambda in the beta rows
        extra(v + nd + 1, v + 1 + k) = -1.0;  // U: mu r_N - sum beta
      }
      extra(v + nd + 1, v) = b.mu;
      row += 3;
      v += nd + 2;
      continue;
    }
    const bool lo = b.kind == BlockKind::Unilateral || std::isfinite(b.lower);
    const bool hi = b.kind == BlockKind::Bounded && std::isfinite(b.upper);
    const double lower = b.kind == BlockKind::Unilateral ? 0.0 : b.lower;
    primary[v] = true;
    if (lo && hi) {  // (7.6): r = lo + z1, w1 = u + z2, w2 = (hi - lo) - z1
      L.S(row, v) = 1.0;
      L.g0[row] = lower;
      extra(v, v + 1) = 1.0;
      extra(v + 1, v) = -1.0;
      extraB[v + 1] = b.upper - b.lower;
      v += 2;
    } else if (lo) {  // r = lo + z, w = u
      L.S(row, v) = 1.0;
      L.g0[row] = lower;
      v += 1;
    } else {  // r = hi - z, w = -u
      L.S(row, v) = -1.0;
      L.g0[row] = b.upper;
      v += 1;
    }
    row += 1;
  }
  // M = S^T W~ S (primary rows) + extras; b = S^T (W~ g0 + q~) (primary rows) + extras.
  const Eigen::MatrixXd WS = Wt * L.S;
  const Eigen::VectorXd u0 = Wt * L.g0 + qt;
  L.M = extra;
  L.b = extraB;
  for (int i = 0; i < lcpSize; ++i) {
    if (!primary[i]) continue;
    L.M.row(i) += L.S.col(i).transpose() * WS;
    L.b[i] += L.S.col(i).dot(u0);
  }
  return L;
}

}  // namespace

std::optional<std::string> LemkeSolver::notApplicable(const ContactProblem& problem) const {
  const int nd = options_.frictionDirections;
  if (nd < 4 || nd % 2 != 0) return "lemke needs an even number of friction directions >= 4";
  int size = 0;
  for (const ConstraintBlock& b : problem.blocks) size += lcpVariables(b, nd);
  if (size > options_.maxLcpSize) {
    std::ostringstream s;
    s << "faceted LCP of " << size << " unknowns exceeds maxLcpSize = " << options_.maxLcpSize;
    return s.str();
  }
  return std::nullopt;
}

void LemkeSolver::solvePrepared(const PreparedProblem& p, const SolveContext& context,
                                Eigen::VectorXd& r, SolverReport& report) const {
  const FacetedLcp L = buildLcp(p, options_);
  LemkeSettings settings = options_.lemke;
  // The common iteration cap (sweeps, Newton steps) may raise the pivot limit but never cut a
  // path short: a basis with z0 still in it answers nothing (the World's cap of 200 did that to
  // every island above ~20 contacts: residuals up to 1e13 were applied).
  const int ownLimit =
      settings.maxPivots > 0 ? settings.maxPivots : std::max(50, 10 * static_cast<int>(L.b.size()));
  settings.maxPivots = std::max(ownLimit, context.options().maxIterations);
  const LcpResult lcp = solveLcpLemke(L.M, L.b, settings);
  report.iterations = lcp.pivots;
  report.nativeResidual = lcp.error;
  report.nativeResidualName =
      "faceted LCP error max(-min z, -min w, |z.w|) / (1 + |b|inf (1 + |z|inf)) (7.4), LCP "
      "built from W / max diag W";
  if (lcp.status == LcpStatus::NumericalFailure) {
    report.status = SolverStatus::NumericalFailure;
    report.note("lemke: non-finite tableau; start returned");
    return;
  }
  // Recovery (7.4): r_c = S z + g0, r_f = -W_ff^-1 (W_fc r_c + q_f) (7.5).
  const Eigen::VectorXd rc = L.S * lcp.z + L.g0;
  Eigen::VectorXd candidate = Eigen::VectorXd::Zero(p.size());
  for (size_t i = 0; i < L.c.size(); ++i) candidate[L.c[i]] = rc[static_cast<int>(i)];
  if (!L.f.empty()) {
    const Eigen::VectorXd rf =
        -Eigen::PartialPivLU<Eigen::MatrixXd>(L.Wff).solve(L.Wfc * rc + L.qf);
    for (size_t i = 0; i < L.f.size(); ++i) candidate[L.f[i]] = rf[static_cast<int>(i)];
  }
  if (!candidate.allFinite()) {
    report.status = SolverStatus::NumericalFailure;
    report.note("lemke: non-finite recovery; start returned");
    return;
  }
  r = candidate;
  Eigen::VectorXd u;
  const double e = p.residual(r, u);
  std::ostringstream msg;
  msg << "lemke: " << lcpStatusName(lcp.status) << " after " << lcp.pivots
      << " pivots on an LCP of " << L.b.size() << " unknowns (n_d = " << options_.frictionDirections
      << "), LCP error " << lcp.error << ", exact-cone e_rel " << e;
  switch (lcp.status) {
    case LcpStatus::Solved:
      report.status = e <= context.tolerance() ? SolverStatus::Converged : SolverStatus::Stalled;
      if (e > context.tolerance()) msg << " (faceted-cone error: sliding directions on facets)";
      break;
    case LcpStatus::Ray:
      report.status = SolverStatus::Stalled;
      msg << "; RAY TERMINATION: no solution along this path (infeasible bias on a null "
             "direction of W, docs/solver-derivations.md (7.7)); last basis returned";
      break;
    case LcpStatus::PivotLimit:
      report.status = SolverStatus::MaxIterations;
      msg << "; pivot limit reached; last basis returned";
      break;
    case LcpStatus::NumericalFailure:
      break;
  }
  report.note(msg.str());
}

}  // namespace coulomb::solvers
