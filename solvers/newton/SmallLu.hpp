#pragma once
// P A = L U of a small dense matrix in place and its solve, written out: the algorithm of Eigen's
// unblocked PartialPivLU (the same operations in the same order), for the systems where Eigen's
// dynamic-size column and outer products, or its fixed-size solve through the general triangular
// solver, cost several times the arithmetic. Used by the dense path of NewtonLinearSolver and by
// the pivot blocks of BodySpaceNewtonSolve.
#include <Eigen/Core>

#include <cmath>
#include <utility>

namespace coulomb::solvers {

/// Column-major with leading dimension lda, partial pivoting by rows; transpositions[k] is the row
/// swapped with row k. A zero pivot leaves its column unscaled (as Eigen): callers check the
/// pivots (smallLuPivotsUsable) or the solution's residual.
inline void smallLuInPlace(double* a, Eigen::Index lda, int m, int* transpositions) {
  for (int k = 0; k < m; ++k) {
    double* colK = a + k * lda;
    int pivot = k;
    double biggest = std::abs(colK[k]);
    for (int i = k + 1; i < m; ++i)
      if (std::abs(colK[i]) > biggest) {
        biggest = std::abs(colK[i]);
        pivot = i;
      }
    transpositions[k] = pivot;
    if (pivot != k)
      for (int j = 0; j < m; ++j) std::swap(a[j * lda + k], a[j * lda + pivot]);
    if (biggest == 0.0) continue;
    const double diagonal = colK[k];
    for (int i = k + 1; i < m; ++i) colK[i] /= diagonal;
    for (int j = k + 1; j < m; ++j) {
      double* colJ = a + j * lda;
      const double factor = colJ[k];
      for (int i = k + 1; i < m; ++i) colJ[i] -= colK[i] * factor;
    }
  }
}

/// Every pivot of smallLuInPlace's factors nonzero and finite.
inline bool smallLuPivotsUsable(const double* a, Eigen::Index lda, int m) {
  for (int k = 0; k < m; ++k) {
    const double pivot = a[k * lda + k];
    if (!(std::abs(pivot) > 0.0) || !std::isfinite(pivot)) return false;
  }
  return true;
}

/// x := U^-1 L^-1 x for the factors of smallLuInPlace (row transpositions already applied to x).
inline void smallLuSolveInPlace(const double* a, Eigen::Index lda, int m, double* x) {
  for (int k = 0; k < m; ++k) {  // L unit lower, by columns
    const double xk = x[k];
    const double* colK = a + k * lda;
    for (int i = k + 1; i < m; ++i) x[i] -= colK[i] * xk;
  }
  for (int k = m - 1; k >= 0; --k) {  // U upper, by columns
    const double* colK = a + k * lda;
    x[k] /= colK[k];
    const double xk = x[k];
    for (int i = 0; i < k; ++i) x[i] -= colK[i] * xk;
  }
}

/// x := A^-1 x: the row transpositions, then smallLuSolveInPlace.
inline void smallLuSolve(const double* a, Eigen::Index lda, int m, const int* transpositions,
                         double* x) {
  for (int k = 0; k < m; ++k)
    if (transpositions[k] != k) std::swap(x[k], x[transpositions[k]]);
  smallLuSolveInPlace(a, lda, m, x);
}

}  // namespace coulomb::solvers
