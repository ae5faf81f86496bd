#include <coulomb/solvers/newton/BodySpaceNewtonSolve.hpp>

#include <Eigen/LU>

#include <algorithm>
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

}  // namespace

double BodySpaceNewtonSolve::bodySpaceCost(const BodySpaceDelassus& W) {
  const double m = 6.0 * W.bodyCount();
  double blocks = 0.0;  // per block of k rows on s sides: F = E_b J_b, s k^2 6, then G F, s^2 36 k
  for (int b = 0; b < W.blockCount(); ++b) {
    const double k = W.blockSize(b);
    const double s = (W.blockBody(b, 0) >= 0 ? 1.0 : 0.0) + (W.blockBody(b, 1) >= 0 ? 1.0 : 0.0);
    blocks += 2.0 * (s * k * k * 6.0 + s * s * 36.0 * k);
  }
  return 2.0 / 3.0 * m * m * m + blocks;
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
    transpositions_.resize(static_cast<std::size_t>(m));
  }
  using Block = Eigen::Map<Eigen::MatrixXd, 0, Eigen::OuterStride<>>;
  Block K(k_.data(), m, m, Eigen::OuterStride<>(k_.rows()));
  K.setIdentity();
  for (int b = 0; b < blocks; ++b) {
    const int k = W.blockSize(b);
    const Eigen::Matrix3d D = jac[b].B + shift * jac[b].A;
    if (!invertBlock(D, k, dInverse_[b])) return false;
    e_[b].setZero();
    e_[b].topLeftCorner(k, k) = dInverse_[b].topLeftCorner(k, k) * jac[b].A.topLeftCorner(k, k);
    const int row0 = offset[b];
    for (int t = 0; t < 2; ++t) {
      const int bodyT = W.blockBody(b, t);
      if (bodyT < 0) continue;
      double f[3][6];  // F = E_b J_{b,t} (k x 6)
      for (int a = 0; a < k; ++a)
        for (int c = 0; c < 6; ++c) {
          double v = 0.0;
          for (int x = 0; x < k; ++x) v += e_[b](a, x) * W.jacobianRow(row0 + x, t)[c];
          f[a][c] = v;
        }
      for (int s = 0; s < 2; ++s) {
        const int bodyS = W.blockBody(b, s);
        if (bodyS < 0) continue;
        for (int c = 0; c < 6; ++c) {
          double* column = &K(6 * bodyS, 6 * bodyT + c);
          for (int a = 0; a < k; ++a) {
            const double* g = W.inverseMassColumn(row0 + a, s);  // (M^-1 J^T) column, 6 values
            const double fa = f[a][c];
            for (int r = 0; r < 6; ++r) column[r] += g[r] * fa;
          }
        }
      }
    }
  }
  int transpositionCount = 0;
  Eigen::internal::partial_lu_impl<double, Eigen::ColMajor, int>::blocked_lu(
      m, m, K.data(), K.outerStride(), transpositions_.data(), transpositionCount);
  for (int i = 0; i < m; ++i)
    if (!(std::abs(K(i, i)) > 0.0) || !std::isfinite(K(i, i))) return false;
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
  // z = K^-1 g (in place in g)
  using Block = Eigen::Map<const Eigen::MatrixXd, 0, Eigen::OuterStride<>>;
  const Block lu(k_.data(), m, m, Eigen::OuterStride<>(k_.rows()));
  auto z = g_.head(m);
  for (int i = 0; i < m; ++i) std::swap(z[i], z[transpositions_[static_cast<std::size_t>(i)]]);
  lu.triangularView<Eigen::UnitLower>().solveInPlace(z);
  lu.triangularView<Eigen::Upper>().solveInPlace(z);
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

}  // namespace coulomb::solvers
