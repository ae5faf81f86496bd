#include <coulomb/solvers/StickingStart.hpp>

#include <algorithm>

namespace coulomb::solvers {
namespace {

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

void StickingStart::buildPattern(const BodySpaceDelassus& W) {
  bodies_ = W.bodyCount();
  pattern_.resize(pairs_.size());
  for (std::size_t p = 0; p < pairs_.size(); ++p)
    pattern_[p] = {static_cast<int>(pairs_[p] >> 32), static_cast<int>(pairs_[p] & 0xffffffffLL)};
  if (!ldltQ_.analyzed(bodies_, pattern_)) ldltQ_.analyze(bodies_, pattern_);
  if (!ldltP_.analyzed(bodies_, pattern_)) ldltP_.analyze(bodies_, pattern_);
}

void StickingStart::accumulate(const BodySpaceDelassus& W, bool inverseMassWeighted) {
  // Sums of outer products in 6 x 6 blocks: per body on the diagonal, per coupled pair
  // (higher body, lower body) below it.
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
  for (Block6& d : diagonal_) d.diagonal().array() += shift;
}

bool StickingStart::compute(const BodySpaceDelassus& W, const Eigen::VectorXd& q,
                            const std::vector<ConstraintBlock>& blocks,
                            const Eigen::VectorXd* warmStart, const Eigen::VectorXd* stepQ) {
  Eigen::VectorXd& r = start_;
  const int blockCount = W.blockCount();
  r.setZero(W.size());
  if (stepQ && stepQ->size() != q.size()) stepQ = nullptr;
  hasStepStart_ = false;
  stepStart_.setZero(W.size());  // sized whether or not it is computed: no allocation on its
                                 // first use in a steady step
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

  accumulate(W, true);
  if (!ldltQ_.factorize(diagonal_, coupling_)) return false;
  accumulate(W, false);
  if (!ldltP_.factorize(diagonal_, coupling_)) return false;
  // One step of iterative refinement with the same factors: the regularization leaves the start
  // about 1e3 kRegularization from the rows' exact stop (1e-9 on a ten-box tower), which a warm
  // start that repeats it adds again at every step; refined, round-off (1e-15).
  auto startOf = [&](const Eigen::VectorXd& velocities, Eigen::VectorXd& out) {
    startFor(W, velocities, out);
    u_ = velocities;
    W.multiplyAdd(out, u_);  // u = W r + velocities
    startFor(W, u_, out);
  };
  startOf(q, r);
  if (stepQ) {
    startOf(*stepQ, stepStart_);
    hasStepStart_ = stepStart_.allFinite();
  }
  return r.allFinite();
}

void StickingStart::startFor(const BodySpaceDelassus& W, const Eigen::VectorXd& velocities,
                             Eigen::VectorXd& out) {
  // Every (row, side, body) of the selected blocks, in order.
  auto forSelectedSides = [&](auto&& visit) {
    for (int b = 0; b < W.blockCount(); ++b) {
      if (!selected(W, b)) continue;
      for (int row = W.blockOffset(b); row < W.blockOffset(b) + W.blockSize(b); ++row)
        for (int side = 0; side < 2; ++side)
          if (const int body = W.blockBody(b, side); body >= 0) visit(row, side, body);
    }
  };
  // f = -Q^-1 M^-1 J^T u: the bodies' impulses that stop the selected rows.
  rhs_.setZero(6 * bodies_);
  forSelectedSides([&](int row, int side, int body) {
    const double* g = W.inverseMassColumn(row, side);
    for (int c = 0; c < 6; ++c) rhs_[6 * body + c] -= g[c] * velocities[row];
  });
  ldltQ_.solve(rhs_, f_);
  // r = J P^-1 f: the least-norm row impulses with J^T r = f.
  ldltP_.solve(f_, x_);
  forSelectedSides([&](int row, int side, int body) {
    const double* j = W.jacobianRow(row, side);
    for (int c = 0; c < 6; ++c) out[row] += j[c] * x_[6 * body + c];
  });
}

}  // namespace coulomb::solvers
