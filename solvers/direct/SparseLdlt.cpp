#include <coulomb/solvers/direct/SparseLdlt.hpp>

#include <coulomb/solvers/direct/SymbolicLdlt.hpp>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>

namespace coulomb::solvers {

void SparseLdlt::analyze(int n, const std::vector<int>& rows, const std::vector<int>& cols) {
  if (n < 0 || rows.size() != cols.size())
    throw std::invalid_argument("SparseLdlt::analyze: bad size or pattern");
  for (std::size_t e = 0; e < rows.size(); ++e)
    if (rows[e] < cols[e] || cols[e] < 0 || rows[e] >= n)
      throw std::invalid_argument("SparseLdlt::analyze: entries must lie in the lower triangle");
  n_ = n;
  rows_ = rows;
  cols_ = cols;

  // Fill-reducing ordering of the symmetric pattern.
  {
    std::vector<std::pair<int, int>> entries;
    entries.reserve(rows.size());
    for (std::size_t e = 0; e < rows.size(); ++e)
      if (rows[e] != cols[e]) entries.emplace_back(rows[e], cols[e]);
    amdOrdering(n, entries, perm_);
  }

  // The ordered upper triangle by column (Davis's input), with every diagonal entry stored and
  // duplicates merged; slotOf_ sends each given entry to its place.
  struct Placed {
    int row, col, entry;
  };
  std::vector<Placed> placed;
  placed.reserve(rows.size() + n);
  for (std::size_t e = 0; e < rows.size(); ++e) {
    const int a = perm_[rows[e]], b = perm_[cols[e]];
    placed.push_back({std::min(a, b), std::max(a, b), static_cast<int>(e)});
  }
  for (int k = 0; k < n; ++k) placed.push_back({k, k, -1});
  std::sort(placed.begin(), placed.end(), [](const Placed& l, const Placed& r) {
    return l.col != r.col ? l.col < r.col : l.row < r.row;
  });
  ap_.assign(n + 1, 0);
  ai_.clear();
  slotOf_.assign(rows.size(), -1);
  for (std::size_t t = 0; t < placed.size(); ++t) {
    const bool fresh =
        t == 0 || placed[t].row != placed[t - 1].row || placed[t].col != placed[t - 1].col;
    if (fresh) {
      ai_.push_back(placed[t].row);
      ++ap_[placed[t].col + 1];
    }
    if (placed[t].entry >= 0) slotOf_[placed[t].entry] = static_cast<int>(ai_.size()) - 1;
  }
  for (int k = 0; k < n; ++k) ap_[k + 1] += ap_[k];
  ax_.assign(ai_.size(), 0.0);

  eliminationTree(n, ap_, ai_, parent_, lnz_, flag_);
  lp_.assign(n + 1, 0);
  for (int k = 0; k < n; ++k) lp_[k + 1] = lp_[k] + lnz_[k];
  li_.assign(lp_[n], 0);
  lx_.assign(lp_[n], 0.0);
  d_.assign(n, 0.0);
  y_.assign(n, 0.0);
  pattern_.assign(n, 0);
  work_.resize(n);
}

bool SparseLdlt::analyzed(int n, const std::vector<int>& rows, const std::vector<int>& cols) const {
  return n == n_ && rows == rows_ && cols == cols_;
}

bool SparseLdlt::factorize(const std::vector<double>& values) {
  return factorizeWith(values, 0.0, nullptr);
}

bool SparseLdlt::factorizeRevealing(const std::vector<double>& values, double pivotFloor,
                                    std::vector<int>& dependent) {
  return factorizeWith(values, pivotFloor, &dependent);
}

bool SparseLdlt::factorizeWith(const std::vector<double>& values, double pivotFloor,
                               std::vector<int>* dependent) {
  if (values.size() != slotOf_.size())
    throw std::invalid_argument("SparseLdlt::factorize: values do not match the pattern");
  std::fill(ax_.begin(), ax_.end(), 0.0);
  for (std::size_t e = 0; e < values.size(); ++e) ax_[slotOf_[e]] += values[e];
  // ldl_numeric: row k of L by a sparse triangular solve, its pattern from the elimination tree.
  const int n = n_;
  for (int k = 0; k < n; ++k) {
    y_[k] = 0.0;
    int top = n;
    flag_[k] = k;
    lnz_[k] = 0;
    for (int p = ap_[k]; p < ap_[k + 1]; ++p) {
      int i = ai_[p];
      y_[i] += ax_[p];
      int length = 0;
      for (; flag_[i] != k; i = parent_[i]) {
        pattern_[length++] = i;
        flag_[i] = k;
      }
      while (length > 0) pattern_[--top] = pattern_[--length];
    }
    d_[k] = y_[k];
    y_[k] = 0.0;
    for (; top < n; ++top) {
      const int i = pattern_[top];
      const double yi = y_[i];
      y_[i] = 0.0;
      const int end = lp_[i] + lnz_[i];
      for (int p = lp_[i]; p < end; ++p) y_[li_[p]] -= lx_[p] * yi;
      const double lki = yi / d_[i];
      d_[k] -= lki * yi;
      li_[end] = k;
      lx_[end] = lki;
      ++lnz_[i];
    }
    if (dependent != nullptr) {
      if (!std::isfinite(d_[k])) return false;
      // A Schur complement this small: the row is a combination of the rows before it, up to
      // round-off and drift (docs/solver-derivations.md (10.3)).
      if (d_[k] <= pivotFloor) {
        dependent->push_back(k);
        d_[k] = pivotFloor;
      }
      continue;
    }
    if (d_[k] == 0.0 || !std::isfinite(d_[k])) return false;
  }
  return true;
}

void SparseLdlt::nullVector(int k, Eigen::VectorXd& n) {
  if (k < 0 || k >= n_) throw std::invalid_argument("SparseLdlt::nullVector: bad row");
  // L^T x = e_k by back substitution: x_j = 0 beyond k, and columns j < k of L only.
  work_.setZero();
  work_[k] = 1.0;
  for (int j = k - 1; j >= 0; --j)
    for (int p = lp_[j]; p < lp_[j + 1]; ++p) work_[j] -= lx_[p] * work_[li_[p]];
  n.resize(n_);
  for (int i = 0; i < n_; ++i) n[i] = work_[perm_[i]];
}

void SparseLdlt::solve(const Eigen::VectorXd& b, Eigen::VectorXd& x) {
  const int n = n_;
  for (int i = 0; i < n; ++i) work_[perm_[i]] = b[i];
  for (int j = 0; j < n; ++j)  // L y = P b
    for (int p = lp_[j]; p < lp_[j + 1]; ++p) work_[li_[p]] -= lx_[p] * work_[j];
  for (int j = 0; j < n; ++j) work_[j] /= d_[j];
  for (int j = n - 1; j >= 0; --j)  // L^T z = D^-1 y
    for (int p = lp_[j]; p < lp_[j + 1]; ++p) work_[j] -= lx_[p] * work_[li_[p]];
  x.resize(n);
  for (int i = 0; i < n; ++i) x[i] = work_[perm_[i]];
}

}  // namespace coulomb::solvers
