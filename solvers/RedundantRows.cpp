#include <coulomb/solvers/RedundantRows.hpp>

#include <coulomb/solvers/BlockSparseMatrix.hpp>
#include <coulomb/solvers/BodySpaceDelassus.hpp>

#include <algorithm>
#include <cmath>

namespace coulomb::solvers {
namespace {

// W_EE's lower triangle as (row, col, value) entries in equality numbering (every diagonal
// entry present); false when W has no entries to read (matrix-free).
bool equalityEntries(const ContactProblem& problem, RedundantRowsWorkspace& work) {
  const auto m = static_cast<int>(work.rowOfEquality.size());
  work.rows.clear();
  work.cols.clear();
  work.values.clear();
  auto add = [&](int a, int b, double value) {
    work.rows.push_back(a);
    work.cols.push_back(b);
    work.values.push_back(value);
  };
  if (const Eigen::MatrixXd* dense = problem.W.denseMatrix()) {
    for (int a = 0; a < m; ++a)
      for (int b = 0; b <= a; ++b)
        if (const double w = (*dense)(work.rowOfEquality[a], work.rowOfEquality[b]);
            w != 0.0 || a == b)
          add(a, b, w);
    return true;
  }
  const BlockSparseMatrix* sparse = problem.W.blockSparseMatrix();
  if (sparse == nullptr) {
    const BodySpaceDelassus* body = problem.W.bodySpaceOperator();
    if (body == nullptr) return false;
    sparse = &body->toBlockSparse();  // cached: Newton reads the same entries
  }
  if (sparse->blockCount() != static_cast<int>(problem.blocks.size())) return false;
  for (int a = 0; a < m; ++a) {
    const int block = work.blockOfEquality[a];
    bool diagonal = false;
    for (int k = sparse->rowBegin(block); k < sparse->rowEnd(block); ++k) {
      const int b = work.equalityOfBlock[sparse->blockColumn(k)];
      if (b < 0 || b > a) continue;
      add(a, b, sparse->blockValues(k)[0]);
      diagonal = diagonal || b == a;
    }
    if (!diagonal) add(a, a, 0.0);
  }
  return true;
}

// Columns [first, last) of N made orthonormal and orthogonal to the columns before them
// (modified Gram-Schmidt, twice); false when one has no length left.
bool orthonormalize(Eigen::MatrixXd& N, int first, int last) {
  for (int pass = 0; pass < 2; ++pass)
    for (int k = first; k < last; ++k) {
      for (int j = 0; j < k; ++j) N.col(k) -= N.col(j).dot(N.col(k)) * N.col(j);
      const double length = N.col(k).norm();
      if (!(length > 0.0) || !std::isfinite(length)) return false;
      N.col(k) /= length;
    }
  return true;
}

// demand -= N N' demand over the first p columns (no temporaries: a steady step allocates none).
void project(RedundantRowsWorkspace& work, int p) {
  const auto N = work.nullVectors.leftCols(p);
  work.along.noalias() = N.transpose() * work.demand;
  work.demand.noalias() -= N * work.along;
}

// y = W_EE x from the lower-triangle entries.
void multiplyEntries(const RedundantRowsWorkspace& work, const Eigen::VectorXd& x,
                     Eigen::VectorXd& y) {
  y.setZero(x.size());
  for (std::size_t e = 0; e < work.values.size(); ++e) {
    const int r = work.rows[e], c = work.cols[e];
    y[r] += work.values[e] * x[c];
    if (r != c) y[c] += work.values[e] * x[r];
  }
}

}  // namespace

RedundantDemand removeRedundantDemands(ContactProblem& problem, RedundantRowsWorkspace& work) {
  RedundantDemand result;
  work.rowOfEquality.clear();
  work.blockOfEquality.clear();
  work.equalityOfBlock.assign(problem.blocks.size(), -1);
  int row = 0;
  for (std::size_t b = 0; b < problem.blocks.size(); row += problem.blocks[b++].size()) {
    if (problem.blocks[b].kind != BlockKind::Equality) continue;
    work.equalityOfBlock[b] = static_cast<int>(work.rowOfEquality.size());
    work.rowOfEquality.push_back(row);
    work.blockOfEquality.push_back(static_cast<int>(b));
  }
  const auto m = static_cast<int>(work.rowOfEquality.size());
  if (m < 2 || problem.q.size() != row || !equalityEntries(problem, work)) return result;

  // Rank-revealing LDL^T of W_EE (no pivoting beyond the fill-reducing order: a row that is a
  // combination of rows ordered before it leaves a pivot of round-off size).
  if (!work.ldlt.analyzed(m, work.rows, work.cols)) work.ldlt.analyze(m, work.rows, work.cols);
  double scale = 0.0;
  for (std::size_t e = 0; e < work.values.size(); ++e)
    if (work.rows[e] == work.cols[e]) scale = std::max(scale, work.values[e]);
  if (!(scale > 0.0) || !std::isfinite(scale)) return result;
  const double floor = kDependentPivot * scale;
  work.dependent.clear();
  if (!work.ldlt.factorizeRevealing(work.values, floor, work.dependent)) return result;

  // N: one (near) null vector of W_EE per dependent row. Its Rayleigh quotient is at most the
  // pivot, so its angle to the near-null space is about sqrt(pivot / lambda), lambda the smallest
  // independent eigenvalue (1e-3 on the rope bridge): too coarse next to q_E's part in W_EE's
  // range, which is 1e3-1e4 times the demand to remove. One step of inverse iteration with the
  // revealing factors (those of W_EE + D_f, the floor on the dependent pivots) gains about
  // floor / lambda more (docs/solver-derivations.md (10.3)).
  auto p = static_cast<int>(work.dependent.size());
  // Storage for p columns and a few more, kept between calls (only the first p are used).
  if (work.nullVectors.rows() != m || work.nullVectors.cols() < p + 1)
    work.nullVectors.resize(m, std::min(m, p + 4));
  for (int k = 0; k < p; ++k) {
    work.ldlt.nullVector(work.dependent[k], work.vector);
    work.ldlt.solve(work.vector, work.vector);
    work.nullVectors.col(k) = work.vector;
  }
  if (!orthonormalize(work.nullVectors, 0, p)) return result;
  work.demand.resize(m);
  for (int a = 0; a < m; ++a) work.demand[a] = problem.q[work.rowOfEquality[a]];
  work.original = work.demand;  // for the total removed
  project(work, p);
  // Directions the pivots hide: a pivot bounds its direction's eigenvalue from above only, and
  // while the rope bridge's boxes land one loop direction has an eigenvalue of 2e-9 of the scale
  // behind a pivot above the floor. Two steps of inverse iteration from the demand left find the
  // near-null direction it still has a part along (the only ones that matter); the direction is
  // taken when its Rayleigh quotient on W_EE is within the floor, then the search repeats.
  while (p < m) {
    work.vector = work.demand;
    for (int step = 0; step < 2; ++step) {
      work.ldlt.solve(work.vector, work.vector);
      for (int j = 0; j < p; ++j)
        work.vector -= work.nullVectors.col(j).dot(work.vector) * work.nullVectors.col(j);
    }
    const double length = work.vector.norm();
    if (!(length > 0.0) || !std::isfinite(length)) break;
    work.vector /= length;
    multiplyEntries(work, work.vector, work.product);
    if (!(work.vector.dot(work.product) <= floor)) break;
    if (work.nullVectors.cols() < p + 1)
      work.nullVectors.conservativeResize(m, std::min(m, 2 * p + 2));
    work.nullVectors.col(p) = work.vector;
    if (!orthonormalize(work.nullVectors, p, p + 1)) break;
    ++p;
    project(work, p);
  }
  if (p == 0 || !work.demand.allFinite()) return result;
  for (int a = 0; a < m; ++a) problem.q[work.rowOfEquality[a]] = work.demand[a];
  result.removed = (work.original - work.demand).norm();
  result.combinations = p;
  return result;
}

}  // namespace coulomb::solvers
