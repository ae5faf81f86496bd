#pragma once
// Lemke's complementary pivoting on a dense LCP (docs/solver-derivations.md Algorithm 7.1; Cottle,
// Pang, Stone, The Linear Complementarity Problem, 1992, section 4.4):
//   find z >= 0 with w = M z + b >= 0 and z^T w = 0,
// covering vector d = (1, ..., 1), tableau [b | I | -M | -d], lexicographic ratio test on the rows
// of B^-1 (the anti-cycling rule that makes every pivot strictly decrease the lexicographic
// objective, so no basis repeats), floating-point safeguards (i)-(ii) against spurious rays on
// rank-deficient M, a pivot limit, and a distinct status for the secondary-ray termination.
// The path follows a perturbed b (the lexicographic rule is the symbolic form of the perturbation
// b + (eps, eps^2, ...), CPS92 chapter 4): on degenerate problems (redundant contacts: many basic
// variables at zero) the lexicographic rule decides among rounding noise in floating point and the
// path ends on spurious rays; a numeric perturbation far above the noise and far below the
// tolerance removes the ties, and the final basis is solved again with the true b.
#include <Eigen/Core>

namespace coulomb::solvers {

enum class LcpStatus {
  Solved,  // z0 left the basis (or was negligible): z solves the LCP
  Ray,  // secondary ray: no blocking row for the entering column (docs/solver-derivations.md (7.7))
  PivotLimit,        // maxPivots reached (cycling or a too small limit)
  NumericalFailure,  // non-finite tableau entry
};
const char* lcpStatusName(LcpStatus status);

struct LemkeSettings {
  // [pivots] 0 = max(50, 10 size) (docs/solver-derivations.md 7, "Floating-point safeguards").
  int maxPivots = 0;
  // Lexicographic tie-breaking on B^-1 (default). Off = ties go to the smallest row index, the
  // textbook rule that can cycle on degenerate problems (kept for the test that shows it).
  bool lexicographic = true;
  // [-] pivot tolerance relative to max|M| (tau of Algorithm 7.1).
  double pivotTolerance = 1e-12;
  // [-] relative tolerance under which two ratios tie.
  double tieTolerance = 1e-12;
  // [pivots] between refactorizations of the tableau from the original data (B^-1 by LU), also
  // done before a ray is declared; 0 = max(50, size); < 0 = never (default). The final basis is
  // always also solved afresh and the better of the two answers kept. Default never: with the
  // perturbation below it changes no corpus answer and costs 2-4x (before the perturbation, on
  // degenerate paths, fresh solves of nearly singular bases were far worse, LCP errors 1e2..1e13).
  int refactorInterval = -1;
  // [-] a pivot below this times the largest entry of its column is checked on a fresh tableau
  // (refactorization from the original data) before it is taken: on the near-singular bases of
  // redundant contacts such an entry is mostly rounding (a 40-contact box stack of a simulation:
  // pivot 5.9e-10, next pivot 5.7e9, a negative basic value, cycling to the pivot limit; with the
  // check, 2 refactorizations and solved in 123 pivots). At most 20 per path; a path with checks
  // that has not ended on an accurate solution within max(50, 2 size) pivots is followed by the
  // plain path (no checks) and the better answer kept (see solveLcpLemke). 0 = never (one plain
  // path).
  double pivotCheckRatio = 1e-7;
  // [-] perturbation of b relative to |b|_inf (positive, distinct per row) that the path follows;
  // the final basis is solved with the true b. 0 = none.
  double perturbation = 1e-10;
};

struct LcpResult {
  LcpStatus status = LcpStatus::NumericalFailure;
  Eigen::VectorXd z;  // always finite, size of b (0 on failure)
  Eigen::VectorXd w;  // M z + b recomputed
  int pivots = 0;
  // max(-min z, -min w, |z^T w|) / (1 + |b|_inf (1 + |z|_inf)): the native LCP error.
  double error = 0.0;
};

// The native error of a candidate z (w recomputed).
double lcpError(const Eigen::MatrixXd& M, const Eigen::VectorXd& b, const Eigen::VectorXd& z,
                Eigen::VectorXd& w);

LcpResult solveLcpLemke(const Eigen::MatrixXd& M, const Eigen::VectorXd& b,
                        const LemkeSettings& settings = {});

}  // namespace coulomb::solvers
