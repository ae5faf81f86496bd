#include <coulomb/solvers/direct/EqualityLdltSolver.hpp>

#include <vector>

namespace coulomb::solvers {

std::optional<std::string> EqualityLdltSolver::notApplicable(const ContactProblem& problem) const {
  for (const ConstraintBlock& b : problem.blocks)
    if (b.kind != BlockKind::Equality)
      return std::string("ldlt solves equality rows only (a ") + blockKindName(b.kind) +
             " block is present)";
  return std::nullopt;
}

void EqualityLdltSolver::solvePrepared(const PreparedProblem& p, const SolveContext& context,
                                       Eigen::VectorXd& r, SolverReport& report) const {
  const BlockSparseMatrix& W = p.W;
  const int n = p.size();
  // The lower triangle, straight from the block rows, in a fixed order: the pattern of the last
  // solve is recognised and its analysis (ordering, elimination tree) reused.
  Workspace& w = workspace_;
  w.rows.clear();
  w.cols.clear();
  w.values.clear();
  for (int b = 0; b < W.blockCount(); ++b) {
    const int rb = W.blockOffset(b), sb = W.blockSize(b);
    for (int k = W.rowBegin(b); k < W.rowEnd(b); ++k) {
      const int c = W.blockColumn(k), rc = W.blockOffset(c), sc = W.blockSize(c);
      const double* v = W.blockValues(k);
      for (int i = 0; i < sb; ++i)
        for (int j = 0; j < sc; ++j)
          if (rc + j <= rb + i) {
            w.rows.push_back(rb + i);
            w.cols.push_back(rc + j);
            w.values.push_back(v[sc * i + j]);
          }
    }
  }
  if (!w.ldlt.analyzed(n, w.rows, w.cols)) w.ldlt.analyze(n, w.rows, w.cols);
  report.iterations = 1;
  report.nativeResidualName = "common residual of the direct solve";
  if (!w.ldlt.factorize(w.values)) {
    report.status = SolverStatus::NumericalFailure;
    report.note("LDL^T factorization failed (W singular: redundant rows?)");
    return;
  }
  w.rhs = -p.q;
  w.ldlt.solve(w.rhs, w.x);
  if (!w.x.allFinite()) {
    report.status = SolverStatus::NumericalFailure;
    report.note("LDL^T solve not finite (W singular: redundant rows?)");
    return;
  }
  r = w.x;
  const double e = p.residual(r, w.u);
  context.record(report, 1, e);
  report.nativeResidual = e;
  report.status = e <= context.tolerance() ? SolverStatus::Converged : SolverStatus::Stalled;
}

}  // namespace coulomb::solvers
