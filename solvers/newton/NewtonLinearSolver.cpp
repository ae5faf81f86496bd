#include <coulomb/solvers/newton/NewtonLinearSolver.hpp>

#include <coulomb/solvers/newton/SmallLu.hpp>

#include <Eigen/KLUSupport>
#include <Eigen/LU>

#include <algorithm>
#include <cmath>

namespace coulomb::solvers {
namespace {

// Eigen's PartialPivLU factors matrices up to this size without blocking.
constexpr int kUnblockedLuSize = 16;

}  // namespace

// KLU with its refactorization: new values on the pattern and pivot order of the last
// factorization, into the same storage (klu_refactor: no pivot search, no allocation). The Newton
// steps of one solve keep the pattern, and their values change little between steps.
struct NewtonLinearSolver::SparseFactor : Eigen::KLU<Eigen::SparseMatrix<double>> {
  // A factorization of the current analysis exists (analyzePattern frees the last one, a failed
  // factorize leaves none).
  [[nodiscard]] bool hasNumeric() const { return m_numeric != nullptr; }
  bool refactorize(Eigen::SparseMatrix<double>& J) {
    if (m_symbolic == nullptr || m_numeric == nullptr) return false;
    return klu_refactor(J.outerIndexPtr(), J.innerIndexPtr(), J.valuePtr(), m_symbolic, m_numeric,
                        &m_common) == 1;
  }
};

NewtonLinearSolver::NewtonLinearSolver(int denseThreshold, double maxSparseDensity)
    : denseThreshold_(denseThreshold), maxSparseDensity_(maxSparseDensity) {}
NewtonLinearSolver::~NewtonLinearSolver() = default;
NewtonLinearSolver::NewtonLinearSolver(NewtonLinearSolver&&) noexcept = default;
NewtonLinearSolver& NewtonLinearSolver::operator=(NewtonLinearSolver&&) noexcept = default;

bool NewtonLinearSolver::samePattern(const BlockSparseMatrix& W,
                                     const std::vector<int>& kept) const {
  if (!analyzed_ || kept != patternKept_ || W.blockSizes() != patternSizes_ ||
      W.nonZeroBlocks() != static_cast<int>(patternColumns_.size()))
    return false;
  for (int b = 0; b < W.blockCount(); ++b) {
    if (W.rowBegin(b) != patternRowStart_[b]) return false;
    for (int k = W.rowBegin(b); k < W.rowEnd(b); ++k)
      if (W.blockColumn(k) != patternColumns_[k]) return false;
  }
  return true;
}

void NewtonLinearSolver::buildPattern(const BlockSparseMatrix& W, const std::vector<int>& offset,
                                      const std::vector<int>& kept, const std::vector<int>& index) {
  const int m = static_cast<int>(kept.size());
  // Entries in assembly order (block row b, kept row a of b, stored block k, kept column c of
  // block column j): count them per column, then give each its compressed position. Rows are
  // visited in increasing order, so every column's rows come out sorted.
  std::vector<int> columns;
  columns.reserve(static_cast<size_t>(W.nonZeros()));
  for (int b = 0; b < W.blockCount(); ++b) {
    const int o = offset[b], s = W.blockSize(b);
    for (int a = 0; a < s; ++a) {
      if (index[o + a] < 0) continue;
      for (int k = W.rowBegin(b); k < W.rowEnd(b); ++k) {
        const int j = W.blockColumn(k), oj = offset[j], sj = W.blockSize(j);
        for (int c = 0; c < sj; ++c)
          if (index[oj + c] >= 0) columns.push_back(index[oj + c]);
      }
    }
  }
  const int nnz = static_cast<int>(columns.size());
  J_.resize(m, m);
  J_.resizeNonZeros(nnz);
  int* outer = J_.outerIndexPtr();
  int* inner = J_.innerIndexPtr();
  std::fill(outer, outer + m + 1, 0);
  for (int col : columns) ++outer[col + 1];
  for (int c = 0; c < m; ++c) outer[c + 1] += outer[c];
  std::vector<int> next(outer, outer + m);
  slots_.resize(columns.size());
  size_t e = 0;
  for (int b = 0; b < W.blockCount(); ++b) {
    const int o = offset[b], s = W.blockSize(b);
    for (int a = 0; a < s; ++a) {
      const int row = index[o + a];
      if (row < 0) continue;
      for (int k = W.rowBegin(b); k < W.rowEnd(b); ++k) {
        const int j = W.blockColumn(k), oj = offset[j], sj = W.blockSize(j);
        for (int c = 0; c < sj; ++c) {
          if (index[oj + c] < 0) continue;
          const int slot = next[columns[e]]++;
          inner[slot] = row;
          slots_[e++] = slot;
        }
      }
    }
  }
  std::fill(J_.valuePtr(), J_.valuePtr() + nnz, 0.0);
  patternSizes_ = W.blockSizes();
  patternRowStart_.resize(W.blockCount());
  patternColumns_.resize(W.nonZeroBlocks());
  for (int b = 0; b < W.blockCount(); ++b) {
    patternRowStart_[b] = W.rowBegin(b);
    for (int k = W.rowBegin(b); k < W.rowEnd(b); ++k) patternColumns_[k] = W.blockColumn(k);
  }
  patternKept_ = kept;
  if (!lu_) lu_ = std::make_unique<SparseFactor>();
  lu_->analyzePattern(J_);
  analyzed_ = true;
  ++stats_.patternAnalyses;
}

void NewtonLinearSolver::fillSparse(const BlockSparseMatrix& W, const std::vector<int>& offset,
                                    const std::vector<NewtonBlockJacobian>& jac,
                                    const std::vector<int>& index, double sigma) {
  double* values = J_.valuePtr();
  size_t e = 0;
  for (int b = 0; b < W.blockCount(); ++b) {
    const int o = offset[b], s = W.blockSize(b);
    const Eigen::Matrix3d& A = jac[b].A;
    const Eigen::Matrix3d& B = jac[b].B;
    for (int a = 0; a < s; ++a) {
      if (index[o + a] < 0) continue;
      for (int k = W.rowBegin(b); k < W.rowEnd(b); ++k) {
        const int j = W.blockColumn(k), oj = offset[j], sj = W.blockSize(j);
        const double* v = W.blockValues(k);
        for (int c = 0; c < sj; ++c) {
          if (index[oj + c] < 0) continue;
          double val = 0;
          for (int t = 0; t < s; ++t) val += A(a, t) * v[sj * t + c];
          if (j == b) val += sigma * A(a, c) + B(a, c);
          values[slots_[e++]] = val;
        }
      }
    }
  }
}

bool NewtonLinearSolver::solve(const BlockSparseMatrix& W, const std::vector<int>& offset,
                               const std::vector<NewtonBlockJacobian>& jac,
                               const std::vector<int>& kept, const std::vector<int>& index,
                               double sigma, const Eigen::VectorXd& rhs, Eigen::VectorXd& x) {
  x.resize(static_cast<Eigen::Index>(kept.size()));
  return solveLeading(W, offset, jac, kept, index, sigma, rhs, x);
}

bool NewtonLinearSolver::solveLeading(const BlockSparseMatrix& W, const std::vector<int>& offset,
                                      const std::vector<NewtonBlockJacobian>& jac,
                                      const std::vector<int>& kept, const std::vector<int>& index,
                                      double sigma, const Eigen::VectorXd& rhsIn,
                                      Eigen::VectorXd& xOut) {
  const int m = static_cast<int>(kept.size());
  if (rhsIn.size() < m || xOut.size() < m) return false;
  const auto rhs = rhsIn.head(m);
  auto x = xOut.head(m);
  if (check_.size() < m) check_.resize(std::max<Eigen::Index>(m, W.size()));
  auto check = check_.head(m);
  double err = 0;
  const double n = W.size();
  factored_ = Factored::None;  // until this factorization succeeds
  factoredRows_ = m;
  if (m <= denseThreshold_ || W.nonZeros() > maxSparseDensity_ * n * n) {
    ++stats_.denseSolves;
    if (dense_.rows() < m) {  // sized to the problem (up to the threshold): |R| varies below it
      const Eigen::Index capacity =
          std::max<Eigen::Index>(m, std::min<Eigen::Index>(W.size(), denseThreshold_));
      dense_.resize(capacity, capacity);
      denseLu_.resize(capacity, capacity);
      transpositions_.resize(static_cast<std::size_t>(capacity));
    }
    using Block = Eigen::Map<Eigen::MatrixXd, 0, Eigen::OuterStride<>>;
    Block J(dense_.data(), m, m, Eigen::OuterStride<>(dense_.rows()));
    Block lu(denseLu_.data(), m, m, Eigen::OuterStride<>(denseLu_.rows()));
    J.setZero();
    for (int b = 0; b < W.blockCount(); ++b) {
      const int o = offset[b], s = W.blockSize(b);
      const Eigen::Matrix3d& A = jac[b].A;
      const Eigen::Matrix3d& B = jac[b].B;
      for (int k = W.rowBegin(b); k < W.rowEnd(b); ++k) {
        const int j = W.blockColumn(k), oj = offset[j], sj = W.blockSize(j);
        const double* v = W.blockValues(k);
        if (s == 3 && sj == 3) {  // two contacts: the 3 x 3 block A W_bj (+ sigma A + B), then
          // scattered; each entry summed in the order of the general loop below
          const int rows[3] = {index[o], index[o + 1], index[o + 2]};
          const int cols[3] = {index[oj], index[oj + 1], index[oj + 2]};
          for (int a = 0; a < 3; ++a) {
            if (rows[a] < 0) continue;
            for (int c = 0; c < 3; ++c) {
              if (cols[c] < 0) continue;
              double val = 0;
              val += A(a, 0) * v[c];
              val += A(a, 1) * v[3 + c];
              val += A(a, 2) * v[6 + c];
              if (j == b) val += sigma * A(a, c) + B(a, c);
              J(rows[a], cols[c]) += val;
            }
          }
          continue;
        }
        for (int a = 0; a < s; ++a) {
          const int row = index[o + a];
          if (row < 0) continue;
          for (int c = 0; c < sj; ++c) {
            const int col = index[oj + c];
            if (col < 0) continue;
            double val = 0;
            for (int t = 0; t < s; ++t) val += A(a, t) * v[sj * t + c];
            if (j == b) val += sigma * A(a, c) + B(a, c);
            J(row, col) += val;
          }
        }
      }
    }
    // P J = L U in place, on the leading block: written out up to kUnblockedLuSize (where
    // Eigen's PartialPivLU does not block either: the same factors), Eigen's blocked algorithm
    // above (its matrix-matrix products pay off there).
    lu = J;
    x = rhs;
    if (m <= kUnblockedLuSize) {
      smallLuInPlace(lu.data(), lu.outerStride(), m, transpositions_.data());
      for (int i = 0; i < m; ++i) std::swap(x[i], x[transpositions_[static_cast<std::size_t>(i)]]);
      smallLuSolveInPlace(lu.data(), lu.outerStride(), m, x.data());
    } else {
      int transpositionCount = 0;
      Eigen::internal::partial_lu_impl<double, Eigen::ColMajor, int>::blocked_lu(
          m, m, lu.data(), lu.outerStride(), transpositions_.data(), transpositionCount);
      for (int i = 0; i < m; ++i) std::swap(x[i], x[transpositions_[static_cast<std::size_t>(i)]]);
      lu.triangularView<Eigen::UnitLower>().solveInPlace(x);
      lu.triangularView<Eigen::Upper>().solveInPlace(x);
    }
    if (!x.allFinite()) return false;
    check.noalias() = J * x;
    check -= rhs;
    err = check.norm();
    factored_ = Factored::Dense;
  } else {
    stats_.lastReusedPattern = samePattern(W, kept);
    if (!stats_.lastReusedPattern) buildPattern(W, offset, kept, index);
    fillSparse(W, offset, jac, index, sigma);
    ++stats_.sparseSolves;
    factored_ = Factored::None;
    // The kept pivot order first; where it is no longer accurate (a pivot grew small with the
    // new values: the residual check below), a factorization with a fresh pivot search.
    const auto solveWith = [&] {
      x = lu_->solve(rhs);
      if (lu_->info() != Eigen::Success || !x.allFinite()) return false;
      check.noalias() = J_ * x;
      check -= rhs;
      err = check.norm();
      return err <= 1e-8 * rhs.norm();
    };
    if (lu_->hasNumeric()) {
      if (lu_->refactorize(J_)) {
        factored_ = Factored::Sparse;
        if (solveWith()) return true;
      }
      ++stats_.refactorFallbacks;
    }
    factored_ = Factored::None;
    lu_->factorize(J_);
    if (lu_->info() != Eigen::Success) return false;
    factored_ = Factored::Sparse;
    return solveWith();
  }
  return err <= 1e-8 * rhs.norm();
}

bool NewtonLinearSolver::solveAgain(const Eigen::VectorXd& rhsIn, Eigen::VectorXd& xOut) {
  const int m = factoredRows_;
  if (factored_ == Factored::None || rhsIn.size() < m || xOut.size() < m) return false;
  const auto rhs = rhsIn.head(m);
  auto x = xOut.head(m);
  auto check = check_.head(m);
  if (factored_ == Factored::Dense) {
    using Block = Eigen::Map<Eigen::MatrixXd, 0, Eigen::OuterStride<>>;
    const Block J(dense_.data(), m, m, Eigen::OuterStride<>(dense_.rows()));
    const Block lu(denseLu_.data(), m, m, Eigen::OuterStride<>(denseLu_.rows()));
    x = rhs;
    for (int i = 0; i < m; ++i) std::swap(x[i], x[transpositions_[static_cast<std::size_t>(i)]]);
    if (m <= kUnblockedLuSize) {
      smallLuSolveInPlace(lu.data(), lu.outerStride(), m, x.data());
    } else {
      lu.triangularView<Eigen::UnitLower>().solveInPlace(x);
      lu.triangularView<Eigen::Upper>().solveInPlace(x);
    }
    if (!x.allFinite()) return false;
    check.noalias() = J * x;
  } else {
    x = lu_->solve(rhs);
    if (lu_->info() != Eigen::Success || !x.allFinite()) return false;
    check.noalias() = J_ * x;
  }
  check -= rhs;
  return check.norm() <= 1e-8 * rhs.norm();
}

}  // namespace coulomb::solvers
