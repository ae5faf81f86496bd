#include <coulomb/solvers/lemke/LemkeLcp.hpp>

#include <Eigen/LU>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace coulomb::solvers {

const char* lcpStatusName(LcpStatus status) {
  switch (status) {
    case LcpStatus::Solved:
      return "solved";
    case LcpStatus::Ray:
      return "ray";
    case LcpStatus::PivotLimit:
      return "pivot_limit";
    case LcpStatus::NumericalFailure:
      return "numerical_failure";
  }
  return "?";
}

double lcpError(const Eigen::MatrixXd& M, const Eigen::VectorXd& b, const Eigen::VectorXd& z,
                Eigen::VectorXd& w) {
  w = M * z + b;
  if (z.size() == 0) return 0.0;
  const double violation = std::max({-z.minCoeff(), -w.minCoeff(), std::abs(z.dot(w)), 0.0});
  return violation / (1.0 + b.lpNorm<Eigen::Infinity>() * (1.0 + z.lpNorm<Eigen::Infinity>()));
}

namespace {

// b + delta |b|_inf theta with theta_i in [0.5, 1) (fractional parts of i times the golden ratio:
// deterministic and all distinct). Makes the problem nondegenerate (no ratio ties, no basic
// variable at zero along the path) for a perturbation far below the answer's tolerance; the
// final basis is then solved with the true b.
Eigen::VectorXd perturbed(const Eigen::VectorXd& b, double delta) {
  Eigen::VectorXd out = b;
  if (delta <= 0) return out;
  const double scale = delta * b.lpNorm<Eigen::Infinity>();
  for (int i = 0; i < b.size(); ++i) {
    const double g = 0.6180339887498949 * (i + 1);
    out[i] += scale * (0.5 + 0.5 * (g - std::floor(g)));
  }
  return out;
}

// Refactorizations a path may spend on small pivots (each O(n^3)): bounds the cost of a path that
// cycles anyway.
constexpr int kMaxPivotChecks = 20;
// [-] LCP error under which the first path's solution is taken without trying the plain path
// (corpus solutions: 1e-18..1e-12).
constexpr double kAccurateError = 1e-9;

using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

// Tableau rows: A x = rhs over the variables w_0..w_{n-1} (columns 0..n-1), z_0..z_{n-1}
// (columns n..2n-1) and the artificial z0 (column 2n). basis[i] is the variable of row i.
class Tableau {
 public:
  Tableau(const Eigen::MatrixXd& M, const Eigen::VectorXd& b)
      : n_(static_cast<int>(b.size())),
        original_(RowMajor::Zero(n_, 2 * n_ + 1)),
        b_(b),
        basis_(n_) {
    for (int i = 0; i < n_; ++i) {
      original_(i, i) = 1.0;
      original_(i, 2 * n_) = -1.0;
      basis_[i] = i;
    }
    original_.middleCols(n_, n_) = -M;
    A_ = original_;
    rhs_ = b;
  }

  // Recomputes the tableau from the original data and the current basis: T = B^-1 [I | -M | -d],
  // rhs = B^-1 b. Removes the rounding accumulated by the eliminations (rank-deficient M makes
  // it large: spurious rays and wrong answers otherwise). Cost about n pivots.
  bool refactor() { return refactor(b_); }
  // The same with another right-hand side (the unperturbed b at the end).
  bool refactor(const Eigen::VectorXd& b) {
    Eigen::MatrixXd B(n_, n_);
    for (int i = 0; i < n_; ++i) B.col(i) = original_.col(basis_[i]);
    const Eigen::PartialPivLU<Eigen::MatrixXd> lu(B);
    Eigen::MatrixXd fresh = lu.solve(Eigen::MatrixXd(original_));
    Eigen::VectorXd rhs = lu.solve(b);
    if (!fresh.allFinite() || !rhs.allFinite()) return false;
    A_ = fresh;
    rhs_ = rhs;
    for (int i = 0; i < n_; ++i) {  // exact unit columns for the basic variables
      A_.col(basis_[i]).setZero();
      A_(i, basis_[i]) = 1.0;
    }
    return true;
  }
  [[nodiscard]] int artificial() const { return 2 * n_; }
  [[nodiscard]] int complement(int v) const { return v < n_ ? v + n_ : v - n_; }
  [[nodiscard]] double entry(int row, int col) const { return A_(row, col); }
  [[nodiscard]] double value(int row) const { return rhs_[row]; }
  [[nodiscard]] int basic(int row) const { return basis_[row]; }
  [[nodiscard]] bool finite() const { return rhs_.allFinite(); }
  [[nodiscard]] double columnMax(int col) const { return A_.col(col).cwiseAbs().maxCoeff(); }

  // Lexicographic comparison of rows i and k: (rhs, row of B^-1) / pivot column entry.
  [[nodiscard]] bool lexLess(int i, int k, int col) const {
    const double ai = A_(i, col), ak = A_(k, col);
    for (int j = 0; j < n_; ++j) {
      const double x = A_(i, j) / ai, y = A_(k, j) / ak;
      if (x < y - 1e-15 * (std::abs(x) + std::abs(y))) return true;
      if (y < x - 1e-15 * (std::abs(x) + std::abs(y))) return false;
    }
    return i < k;
  }

  // Makes `col` basic in `row`; returns the variable that left.
  int pivot(int row, int col) {
    const double p = A_(row, col);
    A_.row(row) /= p;
    rhs_[row] /= p;
    for (int i = 0; i < n_; ++i) {
      if (i == row) continue;
      const double f = A_(i, col);
      if (f == 0.0) continue;
      A_.row(i) -= f * A_.row(row);
      rhs_[i] -= f * rhs_[row];
      A_(i, col) = 0.0;
    }
    const int left = basis_[row];
    basis_[row] = col;
    return left;
  }

  [[nodiscard]] Eigen::VectorXd solution() const {
    Eigen::VectorXd z = Eigen::VectorXd::Zero(n_);
    for (int i = 0; i < n_; ++i)
      if (basis_[i] >= n_ && basis_[i] < 2 * n_) z[basis_[i] - n_] = std::max(rhs_[i], 0.0);
    return z;
  }

 private:
  int n_;
  RowMajor original_;
  Eigen::VectorXd b_;
  RowMajor A_;
  Eigen::VectorXd rhs_;
  std::vector<int> basis_;
};

}  // namespace

namespace {

// One complementary path (Algorithm 7.1 on the perturbed b) of at most maxPivots pivots, with at
// most `pivotChecks` refactorizations for small pivots (LemkeSettings::pivotCheckRatio).
LcpResult followPath(const Eigen::MatrixXd& M, const Eigen::VectorXd& b, const LemkeSettings& s,
                     int pivotChecks, int maxPivots) {
  const int n = static_cast<int>(b.size());
  LcpResult out;
  const double tau = s.pivotTolerance * std::max(M.cwiseAbs().maxCoeff(), 1e-300);
  const double smallZ0 = 1e-12 * b.lpNorm<Eigen::Infinity>();
  const Eigen::VectorXd bp = perturbed(b, s.perturbation);
  Tableau T(M, bp);
  const int z0 = T.artificial();
  // Entering z0: the row of the most negative (perturbed) b (ties lexicographic, column of z0 is
  // -1).
  int row = 0;
  for (int i = 1; i < n; ++i) {
    if (bp[i] < bp[row] - s.tieTolerance * std::abs(bp[row]))
      row = i;
    else if (std::abs(bp[i] - bp[row]) <= s.tieTolerance * std::abs(bp[row]) && s.lexicographic &&
             T.lexLess(i, row, z0))
      row = i;
  }
  // Ratio test over the rows with a positive entry in the entering column; -1 if none.
  auto ratioTest = [&](const Tableau& T, int entering, int& z0Row) {
    int best = -1;
    double bestRatio = 0;
    z0Row = -1;
    for (int i = 0; i < n; ++i) {
      if (T.basic(i) == z0) z0Row = i;
      const double a = T.entry(i, entering);
      if (a <= tau) continue;
      const double ratio = T.value(i) / a;
      if (best < 0 || ratio < bestRatio - s.tieTolerance * std::abs(bestRatio)) {
        best = i;
        bestRatio = ratio;
      } else if (std::abs(ratio - bestRatio) <= s.tieTolerance * std::abs(bestRatio)) {
        // tie: z0's row first (termination), then lexicographic on B^-1 (anti-cycling)
        if (T.basic(best) == z0) continue;
        if (T.basic(i) == z0 || (s.lexicographic && T.lexLess(i, best, entering))) best = i;
      }
    }
    return best;
  };
  const int refactorInterval = s.refactorInterval == 0 ? std::max(50, n) : s.refactorInterval;
  int entering = z0;
  out.status = LcpStatus::PivotLimit;
  for (int k = 0; k < maxPivots; ++k) {
    const int left = T.pivot(row, entering);
    ++out.pivots;
    if (!T.finite()) {
      out.status = LcpStatus::NumericalFailure;
      break;
    }
    if (left == z0) {
      out.status = LcpStatus::Solved;
      break;
    }
    entering = T.complement(left);
    if (refactorInterval > 0 && out.pivots % refactorInterval == 0 && !T.refactor()) {
      out.status = LcpStatus::NumericalFailure;
      break;
    }
    int z0Row = -1;
    int best = ratioTest(T, entering, z0Row);
    if (best >= 0 && pivotChecks > 0 && s.pivotCheckRatio > 0 &&
        T.entry(best, entering) < s.pivotCheckRatio * T.columnMax(entering) && T.refactor()) {
      --pivotChecks;
      best = ratioTest(T, entering, z0Row);  // the same test on the fresh tableau
    }
    if (best < 0 && refactorInterval > 0 && T.refactor())
      best = ratioTest(T, entering, z0Row);  // not a rounding ray?
    if (best < 0) {
      // Safeguards (i)-(ii) of Algorithm 7.1 against spurious rays from tiny pivots.
      if (z0Row >= 0 && T.value(z0Row) <= smallZ0) {
        out.status = LcpStatus::Solved;
        break;
      }
      if (z0Row >= 0 && T.entry(z0Row, entering) > 0) {
        best = z0Row;
      } else {
        out.status = LcpStatus::Ray;
        break;
      }
    }
    row = best;
  }
  out.z = T.solution();
  if (!out.z.allFinite()) out.z.setZero(), out.status = LcpStatus::NumericalFailure;
  out.error = lcpError(M, b, out.z, out.w);
  // The same basis solved afresh with the true b (the path followed the perturbed one); kept only
  // when it is better (a nearly singular basis can make the fresh solve worse than the tableau).
  if (out.status != LcpStatus::NumericalFailure && T.refactor(b)) {
    Eigen::VectorXd w;
    const Eigen::VectorXd z = T.solution();
    const double e = lcpError(M, b, z, w);
    if (z.allFinite() && e < out.error) out.z = z, out.w = w, out.error = e;
  }
  return out;
}

}  // namespace

LcpResult solveLcpLemke(const Eigen::MatrixXd& M, const Eigen::VectorXd& b,
                        const LemkeSettings& s) {
  const int n = static_cast<int>(b.size());
  LcpResult out;
  out.z = Eigen::VectorXd::Zero(n);
  if (n == 0 || b.minCoeff() >= 0) {  // z = 0 solves it
    out.status = LcpStatus::Solved;
    out.error = lcpError(M, b, out.z, out.w);
    return out;
  }
  if (!M.allFinite() || !b.allFinite()) {
    out.status = LcpStatus::NumericalFailure;
    out.w = b;
    return out;
  }
  // The path with small pivots checked on fresh tableaus, then, if it ends without an accurate
  // solution, the plain path, and the better answer (smaller LCP error) is kept with the pivots of
  // both counted. On the near-singular bases of box stacks each of the two solves islands the
  // other fails on (a 10-box tower under lemke!: step 1446 solved in 123 pivots with checks, pivot
  // limit without; step 134 the reverse; step 824 "solved" with checks at an LCP error of 2e-3,
  // exactly in 147 pivots without). The first path gets max(50, 2 size) pivots (every corpus path
  // ends within 0.7 size), so that one that cycles costs little.
  const int maxPivots = s.maxPivots > 0 ? s.maxPivots : std::max(50, 10 * n);
  if (s.pivotCheckRatio <= 0) return followPath(M, b, s, 0, maxPivots);
  LcpResult checked =
      followPath(M, b, s, kMaxPivotChecks, std::min(maxPivots, std::max(50, 2 * n)));
  if (checked.status == LcpStatus::Solved && checked.error <= kAccurateError) return checked;
  LcpResult plain = followPath(M, b, s, 0, maxPivots);
  const auto rank = [](const LcpResult& r) {
    return r.status == LcpStatus::NumericalFailure ? std::numeric_limits<double>::infinity()
                                                   : r.error;
  };
  const int pivots = checked.pivots + plain.pivots;
  LcpResult& best = rank(plain) <= rank(checked) ? plain : checked;
  best.pivots = pivots;
  return best;
}

}  // namespace coulomb::solvers
