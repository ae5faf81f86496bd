#include <coulomb/solvers/direct/EqualityLdltSolver.hpp>

#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>

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
  // Lower triangle only (SimplicialLDLT reads the lower part), straight from the block rows.
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(static_cast<std::size_t>(W.rowEnd(W.blockCount() - 1)) * 3);
  for (int b = 0; b < W.blockCount(); ++b) {
    const int rb = W.blockOffset(b), sb = W.blockSize(b);
    for (int k = W.rowBegin(b); k < W.rowEnd(b); ++k) {
      const int c = W.blockColumn(k), rc = W.blockOffset(c), sc = W.blockSize(c);
      const double* v = W.blockValues(k);
      for (int i = 0; i < sb; ++i)
        for (int j = 0; j < sc; ++j)
          if (rc + j <= rb + i && v[sc * i + j] != 0.0)
            entries.emplace_back(rb + i, rc + j, v[sc * i + j]);
    }
  }
  Eigen::SparseMatrix<double> lower(n, n);
  lower.setFromTriplets(entries.begin(), entries.end());
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>, Eigen::Lower> ldlt(lower);
  report.iterations = 1;
  report.nativeResidualName = "common residual of the direct solve";
  if (ldlt.info() != Eigen::Success) {
    report.status = SolverStatus::NumericalFailure;
    report.note("LDL^T factorization failed (W singular: redundant rows?)");
    return;
  }
  const Eigen::VectorXd x = ldlt.solve(-p.q);
  if (!x.allFinite()) {
    report.status = SolverStatus::NumericalFailure;
    report.note("LDL^T solve not finite (W singular: redundant rows?)");
    return;
  }
  r = x;
  Eigen::VectorXd u;
  const double e = p.residual(r, u);
  context.record(report, 1, e);
  report.nativeResidual = e;
  report.status = e <= context.tolerance() ? SolverStatus::Converged : SolverStatus::Stalled;
}

}  // namespace coulomb::solvers
