#include <coulomb/solvers/newton/BodySpaceNewtonSolve.hpp>

#include <coulomb/solvers/newton/SmallLu.hpp>

#include <algorithm>
#include <array>
#include <cmath>

namespace coulomb::solvers {

namespace {

// D_b^-1 for the leading k x k part of D (k = 1 or 3); false when D is singular to working
// precision (|det| below 1e-14 of its largest entry cubed) or not finite.
bool invertBlock(const Eigen::Matrix3d& D, int k, Eigen::Matrix3d& inverse) {
  inverse.setZero();
  if (k == 1) {
    if (!std::isfinite(D(0, 0)) || D(0, 0) == 0.0) return false;
    inverse(0, 0) = 1.0 / D(0, 0);
    return true;
  }
  const double scale = D.cwiseAbs().maxCoeff();
  const double det = D.determinant();
  if (!std::isfinite(det) || !(std::abs(det) > 1e-14 * scale * scale * scale)) return false;
  inverse = D.inverse();
  return inverse.allFinite();
}

using Matrix6 = Eigen::Matrix<double, 6, 6>;

// x := A^-1 x for a pivot block's P A = L U (smallLuInPlace, column-major 6 x 6), its row order
// `rows` (x's entries in P's order) and 1 / U_kk: the substitutions run on six values held in
// registers, multiplying by the reciprocals. The general smallLuSolve writes x[k] back between
// steps and reads pairs of it with packed loads, which stall on the scalar stores before them;
// with a division on the chain, that was a sixth of a landing step (perf).
void pivotSolve(const double* lu, const std::array<int, 6>& rows, const std::array<double, 6>& inv,
                double* x) {
  double v[6];  // unrolled whole, so that v lives in registers
#pragma GCC unroll 6
  for (int i = 0; i < 6; ++i) v[i] = x[rows[i]];
#pragma GCC unroll 6
  for (int k = 0; k < 6; ++k)  // L unit lower
#pragma GCC unroll 6
    for (int i = k + 1; i < 6; ++i) v[i] -= lu[6 * k + i] * v[k];
#pragma GCC unroll 6
  for (int k = 5; k >= 0; --k) {  // U upper
    v[k] *= inv[k];
#pragma GCC unroll 6
    for (int i = 0; i < k; ++i) v[i] -= lu[6 * k + i] * v[k];
  }
#pragma GCC unroll 6
  for (int i = 0; i < 6; ++i) x[i] = v[i];
}

// The island's body graph as a bodies x bodies mask (row-major): the diagonal, and both entries of
// every pair of bodies that a block acts on; K has this block pattern before elimination.
void markBodyGraph(const BodySpaceDelassus& W, std::vector<char>& mask) {
  const int nb = W.bodyCount();
  mask.assign(static_cast<std::size_t>(nb) * nb, 0);
  for (int i = 0; i < nb; ++i) mask[static_cast<std::size_t>(i) * nb + i] = 1;
  for (int b = 0; b < W.blockCount(); ++b) {
    const int s = W.blockBody(b, 0), t = W.blockBody(b, 1);
    if (s < 0 || t < 0) continue;
    mask[static_cast<std::size_t>(s) * nb + t] = mask[static_cast<std::size_t>(t) * nb + s] = 1;
  }
}

// A sticking contact (5.3a, 5.4a): A = diag(rho_N, rho_T, rho_T), B = 0.
bool sticks(const NewtonBlockJacobian& jac) {
  const Eigen::Matrix3d& A = jac.A;
  return jac.B.isZero(0.0) && A(0, 1) == 0.0 && A(0, 2) == 0.0 && A(1, 0) == 0.0 &&
         A(1, 2) == 0.0 && A(2, 0) == 0.0 && A(2, 1) == 0.0 && A(0, 0) != 0.0 && A(1, 1) != 0.0 &&
         A(2, 2) != 0.0;
}

}  // namespace

double BodySpaceNewtonSolve::bodySpaceCost(const BodySpaceDelassus& W,
                                           const std::vector<NewtonBlockJacobian>& jac,
                                           double eliminationFlops) const {
  double forming = 0.0;  // per block of k rows on s sides
  for (int b = 0; b < W.blockCount(); ++b) {
    const double k = W.blockSize(b);
    const double s = (W.blockBody(b, 0) >= 0 ? 1.0 : 0.0) + (W.blockBody(b, 1) >= 0 ? 1.0 : 0.0);
    if (jac[b].A.isZero(0.0)) continue;  // open
    if (W.blockSize(b) == 3 && sticks(jac[b]))
      forming += 2.0 * s * s * 36.0;  // the couplings over the shift
    else
      forming += 2.0 * (s * k * k * 6.0 + s * s * 36.0 * k);  // F = E_b J_b, then G F
  }
  return forming + eliminationFlops;
}

double BodySpaceNewtonSolve::eliminationFlops(const BodySpaceDelassus& W) {
  const int nb = W.bodyCount();
  if (static_cast<int>(below_.size()) < nb) {
    below_.resize(nb);
    right_.resize(nb);
  }
  markBodyGraph(W, graph_);
  const auto at = [&](int i, int j) -> char& {
    return graph_[static_cast<std::size_t>(i) * nb + j];
  };
  constexpr double pivotLu = 2.0 / 3.0 * 216.0, blockSolve = 2.0 * 216.0, schur = 2.0 * 216.0;
  double flops = 0.0;
  for (int k = 0; k < nb; ++k) {
    int belowCount = 0, rightCount = 0;
    for (int i = k + 1; i < nb; ++i) {
      if (at(i, k)) below_[belowCount++] = i;
      if (at(k, i)) right_[rightCount++] = i;
    }
    flops += pivotLu + rightCount * blockSolve + belowCount * rightCount * schur;
    for (int a = 0; a < belowCount; ++a)
      for (int r = 0; r < rightCount; ++r) at(below_[a], right_[r]) = 1;  // fill
  }
  return flops;
}

double BodySpaceNewtonSolve::contactSpaceCost(int keptRows) {
  const double n = keptRows;
  return 2.0 / 3.0 * n * n * n;
}

bool BodySpaceNewtonSolve::factor(const BodySpaceDelassus& W, const std::vector<int>& offset,
                                  const std::vector<NewtonBlockJacobian>& jac, double shift) {
  W_ = nullptr;
  if (!(shift > 0.0)) return false;
  const int blocks = W.blockCount();
  const int m = 6 * W.bodyCount();
  if (static_cast<int>(dInverse_.size()) < blocks) {
    dInverse_.resize(blocks);
    e_.resize(blocks);
  }
  if (k_.rows() < m) {
    k_.resize(m, m);
  }
  using Block = Eigen::Map<Eigen::MatrixXd, 0, Eigen::OuterStride<>>;
  Block K(k_.data(), m, m, Eigen::OuterStride<>(k_.rows()));
  // K's 6 x 6 blocks on the body graph (the only ones set; blockLu adds its fill): I, plus the
  // terms of M^-1 J^T E J below.
  const int nb = W.bodyCount();
  markBodyGraph(W, nonzero_);
  for (int j = 0; j < nb; ++j)
    for (int i = 0; i < nb; ++i)
      if (nonzero_[static_cast<std::size_t>(i) * nb + j] != 0) {
        if (i == j)
          K.block<6, 6>(6 * i, 6 * j).setIdentity();
        else
          K.block<6, 6>(6 * i, 6 * j).setZero();
      }
  const double inverseShift = 1.0 / shift;
  for (int b = 0; b < blocks; ++b) {
    const int k = W.blockSize(b);
    const Eigen::Matrix3d& A = jac[b].A;
    const int row0 = offset[b];
    if (k == 3 && sticks(jac[b])) {
      // Sticking: D_b = s A_b and E_b = I / s; the block adds its couplings G_s J_t over s,
      // which depend on the factors alone (cached there).
      dInverse_[b] = (shift * A.diagonal()).cwiseInverse().asDiagonal();
      if (!dInverse_[b].allFinite()) return false;
      e_[b] = inverseShift * Eigen::Matrix3d::Identity();
      const double* couplings = W.sideCouplings(b);
      for (int t = 0; t < 2; ++t) {
        const int bodyT = W.blockBody(b, t);
        if (bodyT < 0) continue;
        for (int s = 0; s < 2; ++s) {
          const int bodyS = W.blockBody(b, s);
          if (bodyS < 0) continue;
          K.block<6, 6>(6 * bodyS, 6 * bodyT) +=
              inverseShift * Matrix6::Map(couplings + 36 * (2 * s + t));
        }
      }
      continue;
    }
    const Eigen::Matrix3d D = jac[b].B + shift * A;
    if (!invertBlock(D, k, dInverse_[b])) return false;
    if (k == 3) {
      e_[b].noalias() = dInverse_[b] * A;
    } else {
      e_[b].setZero();
      e_[b](0, 0) = dInverse_[b](0, 0) * A(0, 0);
    }
    if (A.isZero(0.0)) continue;  // E_b = 0 (an open contact): nothing in K
    if (k == 3) {  // a contact: fixed-size products (the rows of one side are 12 doubles apart)
      using Rows =
          Eigen::Map<const Eigen::Matrix<double, 3, 6, Eigen::RowMajor>, 0, Eigen::OuterStride<12>>;
      using Columns = Eigen::Map<const Eigen::Matrix<double, 6, 3>, 0, Eigen::OuterStride<12>>;
      for (int t = 0; t < 2; ++t) {
        const int bodyT = W.blockBody(b, t);
        if (bodyT < 0) continue;
        const Eigen::Matrix<double, 3, 6> F = e_[b] * Rows(W.jacobianRow(row0, t));
        for (int s = 0; s < 2; ++s) {
          const int bodyS = W.blockBody(b, s);
          if (bodyS < 0) continue;
          K.block<6, 6>(6 * bodyS, 6 * bodyT).noalias() +=
              Columns(W.inverseMassColumn(row0, s)) * F;
        }
      }
      continue;
    }
    for (int t = 0; t < 2; ++t) {  // a scalar row
      const int bodyT = W.blockBody(b, t);
      if (bodyT < 0) continue;
      const double e = e_[b](0, 0);
      const double* j = W.jacobianRow(row0, t);
      for (int s = 0; s < 2; ++s) {
        const int bodyS = W.blockBody(b, s);
        if (bodyS < 0) continue;
        const double* g = W.inverseMassColumn(row0, s);
        for (int c = 0; c < 6; ++c)
          for (int r = 0; r < 6; ++r) K(6 * bodyS + r, 6 * bodyT + c) += g[r] * e * j[c];
      }
    }
  }
  if (!blockLu(W)) return false;
  W_ = &W;
  offset_ = &offset;
  m_ = m;
  return true;
}

void BodySpaceNewtonSolve::solve(const Eigen::VectorXd& b, Eigen::VectorXd& x) {
  const BodySpaceDelassus& W = *W_;
  const std::vector<int>& offset = *offset_;
  const int n = W.size(), m = m_;
  if (y_.size() < n) {
    y_.resize(n);
    jz_.resize(n);
  }
  if (g_.size() < m) g_.resize(m);
  if (x.size() != n) x.resize(n);
  // y = D^-1 b, g = M^-1 J^T y
  g_.head(m).setZero();
  for (int blk = 0; blk < W.blockCount(); ++blk) {
    const int o = offset[blk], k = W.blockSize(blk);
    for (int a = 0; a < k; ++a) {
      double v = 0.0;
      for (int c = 0; c < k; ++c) v += dInverse_[blk](a, c) * b[o + c];
      y_[o + a] = v;
    }
    W.addBlockImpulse(blk, y_.data() + o, g_);
  }
  blockSolve(g_);  // z = K^-1 g in place
  // x = y - E J z
  jz_.head(n).setZero();
  W.addRowVelocities(g_, jz_.data());
  for (int blk = 0; blk < W.blockCount(); ++blk) {
    const int o = offset[blk], k = W.blockSize(blk);
    for (int a = 0; a < k; ++a) {
      double v = y_[o + a];
      for (int c = 0; c < k; ++c) v -= e_[blk](a, c) * jz_[o + c];
      x[o + a] = v;
    }
  }
}

// K = L U by 6 x 6 blocks in the bodies' order, skipping the blocks that are zero in K and stay
// zero (K's pattern, nonzero_ as factor set it, is the island's body graph: a column of boxes is
// block-tridiagonal and its factors keep that pattern), pivoting inside each diagonal block: M K =
// M + J^T E J is symmetric positive definite where the contacts stick (E = I / s), so the diagonal
// blocks are the natural pivots; the caller's residual check covers the rest. Right-looking: after
// step k, K_kj (j > k) holds K_kk^-1 K_kj and the blocks below and right of k are Schur-updated.
bool BodySpaceNewtonSolve::blockLu(const BodySpaceDelassus& W) {
  const int nb = W.bodyCount(), m = 6 * nb;
  const Eigen::Index lda = k_.rows();
  if (static_cast<int>(pivotLu_.size()) < nb) {
    pivotLu_.resize(nb);
    pivotRows_.resize(nb);
    pivotInverse_.resize(nb);
    pivotOrder_.resize(nb);
  }
  if (static_cast<int>(below_.size()) < nb) {
    below_.resize(nb);
    right_.resize(nb);
  }
  using Block6 = Eigen::Map<Eigen::Matrix<double, 6, 6>, 0, Eigen::OuterStride<>>;
  const auto block = [&](int i, int j) {
    return Block6(k_.data() + 6 * i + 6 * j * lda, 6, 6, Eigen::OuterStride<>(lda));
  };
  const auto nz = [&](int i, int j) -> char& {
    return nonzero_[static_cast<std::size_t>(i) * nb + j];
  };
  for (int k = 0; k < nb; ++k) {
    Matrix6& lu = pivotLu_[k];
    lu = block(k, k);
    smallLuInPlace(lu.data(), 6, 6, pivotRows_[k].data());
    if (!smallLuPivotsUsable(lu.data(), 6, 6)) return false;
    std::array<int, 6>& order = pivotOrder_[k];  // the transpositions as one permutation
    for (int i = 0; i < 6; ++i) {
      order[i] = i;
      pivotInverse_[k][i] = 1.0 / lu(i, i);
    }
    for (int i = 0; i < 6; ++i) std::swap(order[i], order[pivotRows_[k][i]]);
    int belowCount = 0, rightCount = 0;
    for (int i = k + 1; i < nb; ++i) {
      if (nz(i, k)) below_[belowCount++] = i;
      if (nz(k, i)) right_[rightCount++] = i;
    }
    for (int r = 0; r < rightCount; ++r) {
      Block6 kj = block(k, right_[r]);
      for (int c = 0; c < 6; ++c) pivotSolve(lu.data(), order, pivotInverse_[k], kj.col(c).data());
    }
    for (int a = 0; a < belowCount; ++a) {
      const int i = below_[a];
      const Matrix6 ik = block(i, k);
      for (int r = 0; r < rightCount; ++r) {
        const int j = right_[r];
        if (!nz(i, j)) {
          block(i, j).setZero();
          nz(i, j) = 1;
        }
        block(i, j).noalias() -= ik * block(k, j);
      }
    }
  }
  m_ = m;
  return true;
}

// z = K^-1 z with blockLu's factors: L (the Schur-updated lower blocks and the diagonal blocks'
// LU) forward, then the unit upper blocks backward.
void BodySpaceNewtonSolve::blockSolve(Eigen::VectorXd& z) const {
  const int nb = m_ / 6;
  const Eigen::Index lda = k_.rows();
  using Block6 = Eigen::Map<const Eigen::Matrix<double, 6, 6>, 0, Eigen::OuterStride<>>;
  const auto block = [&](int i, int j) {
    return Block6(k_.data() + 6 * i + 6 * j * lda, 6, 6, Eigen::OuterStride<>(lda));
  };
  const auto nz = [&](int i, int j) { return nonzero_[static_cast<std::size_t>(i) * nb + j] != 0; };
  for (int k = 0; k < nb; ++k) {
    Eigen::Matrix<double, 6, 1> v = z.segment<6>(6 * k);
    for (int i = 0; i < k; ++i)
      if (nz(k, i)) v.noalias() -= block(k, i) * z.segment<6>(6 * i);
    pivotSolve(pivotLu_[k].data(), pivotOrder_[k], pivotInverse_[k], v.data());
    z.segment<6>(6 * k) = v;
  }
  for (int k = nb - 1; k >= 0; --k) {
    Eigen::Matrix<double, 6, 1> v = z.segment<6>(6 * k);
    for (int j = k + 1; j < nb; ++j)
      if (nz(k, j)) v.noalias() -= block(k, j) * z.segment<6>(6 * j);
    z.segment<6>(6 * k) = v;
  }
}

}  // namespace coulomb::solvers
