#include <coulomb/solvers/StickingStart.hpp>

#include <algorithm>

namespace coulomb::solvers {
namespace {

constexpr int kDiagonalEntries = 21;  // lower triangle of a 6 x 6 block
constexpr int kPairEntries = 36;

long long pairKey(int a, int b) {
  return (static_cast<long long>(std::max(a, b)) << 32) | static_cast<long long>(std::min(a, b));
}

bool selects(const ConstraintBlock& block, double firstVelocity, double lastImpulse) {
  switch (block.kind) {
    case BlockKind::Equality:
    case BlockKind::Bounded:
      return true;
    case BlockKind::Unilateral:
    case BlockKind::Contact3D:
      return firstVelocity <= 0.0 || lastImpulse > 0.0;  // it would push, or it pushed
  }
  return false;
}

}  // namespace

bool StickingStart::selected(const BodySpaceDelassus& W, int b) const {
  if (W.blockBody(b, 0) < 0 && W.blockBody(b, 1) < 0) return false;
  const int first = W.blockOffset(b);
  return selects((*blocks_)[b], (*q_)[first], warmStart_ ? (*warmStart_)[first] : 0.0);
}

int StickingStart::pairOf(const BodySpaceDelassus& W, int b) const {
  const int body0 = W.blockBody(b, 0), body1 = W.blockBody(b, 1);
  if (body0 < 0 || body1 < 0 || body0 == body1) return -1;
  return static_cast<int>(std::lower_bound(pairs_.begin(), pairs_.end(), pairKey(body0, body1)) -
                          pairs_.begin());
}

int StickingStart::diagonalSlot(int body, int i, int j) const {
  return kDiagonalEntries * body + i * (i + 1) / 2 + j;
}

int StickingStart::pairSlot(int pair, int i, int j) const {
  return kDiagonalEntries * bodies_ + kPairEntries * pair + 6 * i + j;
}

void StickingStart::buildPattern(const BodySpaceDelassus& W) {
  bodies_ = W.bodyCount();
  const std::size_t entries = static_cast<std::size_t>(kDiagonalEntries) * bodies_ +
                              static_cast<std::size_t>(kPairEntries) * pairs_.size();
  rows_.resize(entries);
  cols_.resize(entries);
  for (int a = 0; a < bodies_; ++a)
    for (int i = 0; i < 6; ++i)
      for (int j = 0; j <= i; ++j) {
        rows_[diagonalSlot(a, i, j)] = 6 * a + i;
        cols_[diagonalSlot(a, i, j)] = 6 * a + j;
      }
  for (std::size_t p = 0; p < pairs_.size(); ++p) {
    const int high = static_cast<int>(pairs_[p] >> 32);
    const int low = static_cast<int>(pairs_[p] & 0xffffffffLL);
    for (int i = 0; i < 6; ++i)
      for (int j = 0; j < 6; ++j) {
        rows_[pairSlot(static_cast<int>(p), i, j)] = 6 * high + i;
        cols_[pairSlot(static_cast<int>(p), i, j)] = 6 * low + j;
      }
  }
  if (!ldlt_.analyzed(6 * bodies_, rows_, cols_)) ldlt_.analyze(6 * bodies_, rows_, cols_);
}

void StickingStart::accumulate(const BodySpaceDelassus& W, bool inverseMassWeighted,
                               std::vector<double>& out) {
  // Sums of outer products in full 6 x 6 blocks (fixed-size, vectorized), then their lower
  // triangles in the pattern's order.
  using Block6 = Eigen::Matrix<double, 6, 6>;
  diagonal_.assign(bodies_, Block6::Zero());
  coupling_.assign(pairs_.size(), Block6::Zero());
  using Rows = Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, 6, Eigen::RowMajor>, 0,
                          Eigen::OuterStride<12>>;  // one side's rows: 12 numbers apart
  auto rows = [&](int b, int side) {
    const int row = W.blockOffset(b);
    return Rows(inverseMassWeighted ? W.inverseMassColumn(row, side) : W.jacobianRow(row, side),
                W.blockSize(b), 6);
  };
  for (int b = 0; b < W.blockCount(); ++b) {
    if (!selected(W, b)) continue;
    const int body0 = W.blockBody(b, 0), body1 = W.blockBody(b, 1);
    if (body0 >= 0) diagonal_[body0].noalias() += rows(b, 0).transpose() * rows(b, 0);
    if (body1 >= 0) diagonal_[body1].noalias() += rows(b, 1).transpose() * rows(b, 1);
    if (body0 < 0 || body1 < 0) continue;
    if (body0 == body1) {  // both sides on one body: the cross terms land on its diagonal
      const Block6 cross = rows(b, 0).transpose() * rows(b, 1);
      diagonal_[body0] += cross + cross.transpose();
    } else if (body0 > body1) {
      coupling_[pairOf(W, b)].noalias() += rows(b, 0).transpose() * rows(b, 1);
    } else {
      coupling_[pairOf(W, b)].noalias() += rows(b, 1).transpose() * rows(b, 0);
    }
  }
  // The same small multiple of the identity on the whole diagonal (see the header).
  double trace = 0.0;
  for (const Block6& d : diagonal_) trace += d.trace();
  const double shift = kRegularization * trace / (6.0 * bodies_);
  out.resize(rows_.size());
  for (int a = 0; a < bodies_; ++a)
    for (int i = 0; i < 6; ++i)
      for (int j = 0; j <= i; ++j)
        out[diagonalSlot(a, i, j)] = diagonal_[a](i, j) + (i == j ? shift : 0.0);
  for (std::size_t p = 0; p < pairs_.size(); ++p)
    for (int i = 0; i < 6; ++i)
      for (int j = 0; j < 6; ++j) out[pairSlot(static_cast<int>(p), i, j)] = coupling_[p](i, j);
}

bool StickingStart::compute(const BodySpaceDelassus& W, const Eigen::VectorXd& q,
                            const std::vector<ConstraintBlock>& blocks,
                            const Eigen::VectorXd* warmStart, Eigen::VectorXd& r) {
  const int blockCount = W.blockCount();
  r.setZero(W.size());
  if (W.bodyCount() == 0 || static_cast<int>(blocks.size()) != blockCount || q.size() != W.size())
    return false;
  if (warmStart && warmStart->size() != W.size()) warmStart = nullptr;
  q_ = &q;
  blocks_ = &blocks;
  warmStart_ = warmStart;
  // Every coupled pair is in the pattern, selected or not: resting contacts' q_N flickers around
  // 0 from step to step, and the pattern (and its analysis) stays as long as the contacts do.
  pairs_.clear();
  bool any = false;
  for (int b = 0; b < blockCount; ++b) {
    const int body0 = W.blockBody(b, 0), body1 = W.blockBody(b, 1);
    // A manifold's points are consecutive blocks: one entry per manifold before the sort.
    if (body0 >= 0 && body1 >= 0 && body0 != body1 &&
        (pairs_.empty() || pairs_.back() != pairKey(body0, body1)))
      pairs_.push_back(pairKey(body0, body1));
    any = any || selected(W, b);
  }
  if (!any) return false;
  std::sort(pairs_.begin(), pairs_.end());
  pairs_.erase(std::unique(pairs_.begin(), pairs_.end()), pairs_.end());
  buildPattern(W);

  // f = -Q^-1 M^-1 J^T q: the bodies' impulses that stop the selected rows.
  // Every (row, side, body) of the selected blocks, in order.
  auto forSelectedSides = [&](auto&& visit) {
    for (int b = 0; b < blockCount; ++b) {
      if (!selected(W, b)) continue;
      for (int row = W.blockOffset(b); row < W.blockOffset(b) + W.blockSize(b); ++row)
        for (int side = 0; side < 2; ++side)
          if (const int body = W.blockBody(b, side); body >= 0) visit(row, side, body);
    }
  };
  rhs_.setZero(6 * bodies_);
  forSelectedSides([&](int row, int side, int body) {
    const double* g = W.inverseMassColumn(row, side);
    for (int c = 0; c < 6; ++c) rhs_[6 * body + c] -= g[c] * q[row];
  });
  accumulate(W, true, qm_);
  if (!ldlt_.factorize(qm_)) return false;
  ldlt_.solve(rhs_, f_);
  // r = J P^-1 f: the least-norm row impulses with J^T r = f.
  accumulate(W, false, p_);
  if (!ldlt_.factorize(p_)) return false;
  ldlt_.solve(f_, x_);
  forSelectedSides([&](int row, int side, int body) {
    const double* j = W.jacobianRow(row, side);
    for (int c = 0; c < 6; ++c) r[row] += j[c] * x_[6 * body + c];
  });
  return r.allFinite();
}

}  // namespace coulomb::solvers
