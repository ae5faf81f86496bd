#include <coulomb/solvers/BodySpaceDelassus.hpp>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace coulomb::solvers {

BodySpaceDelassus::BodySpaceDelassus(int bodyCount, std::vector<int> blockSizes) {
  size_ = std::move(blockSizes);
  reset(bodyCount);
}

void BodySpaceDelassus::reset(int bodyCount, const std::vector<int>& blockSizes) {
  size_.assign(blockSizes.begin(), blockSizes.end());
  reset(bodyCount);
}

void BodySpaceDelassus::reset(int bodyCount) {
  if (bodyCount < 0) throw std::invalid_argument("BodySpaceDelassus: negative body count");
  bodies_ = bodyCount;
  finitenessKnown_ = false;
  entriesValid_ = false;
  diagonal_.clear();
  couplings_.clear();
  offset_.assign(size_.size() + 1, 0);
  for (std::size_t b = 0; b < size_.size(); ++b) {
    if (size_[b] != 1 && size_[b] != 3)
      throw std::invalid_argument("BodySpaceDelassus: blocks have 1 or 3 rows");
    offset_[b + 1] = offset_[b] + size_[b];
  }
  body_.assign(2 * size_.size(), -1);
  // Not cleared: every reader skips a side without a body (body_ < 0), and setSide writes all of
  // a side's numbers. Zeroing 2 x 12 doubles per row cost 5 % of a resting pyramid's step.
  j_.resize(static_cast<std::size_t>(12) * size());
  g_.resize(static_cast<std::size_t>(12) * size());
}

void BodySpaceDelassus::gather(const int* blocks, int count, BodySpaceDelassus& out) const {
  out.size_.resize(count);
  for (int i = 0; i < count; ++i) out.size_[i] = size_[blocks[i]];
  out.bodies_ = bodies_;
  out.finitenessKnown_ = finitenessKnown_;
  out.finite_ = finite_;
  out.entriesValid_ = false;
  out.diagonal_.clear();
  out.couplings_.clear();
  out.offset_.resize(count + 1);
  out.offset_[0] = 0;
  for (int i = 0; i < count; ++i) out.offset_[i + 1] = out.offset_[i] + out.size_[i];
  out.body_.resize(2 * static_cast<std::size_t>(count));
  out.j_.resize(static_cast<std::size_t>(12) * out.offset_[count]);
  out.g_.resize(out.j_.size());
  for (int i = 0; i < count; ++i) {
    const int b = blocks[i];
    out.body_[2 * i] = body_[2 * b];
    out.body_[2 * i + 1] = body_[2 * b + 1];
    const auto from = static_cast<std::ptrdiff_t>(12) * offset_[b];
    const auto to = static_cast<std::ptrdiff_t>(12) * out.offset_[i];
    std::copy_n(j_.begin() + from, 12 * size_[b], out.j_.begin() + to);
    std::copy_n(g_.begin() + from, 12 * size_[b], out.g_.begin() + to);
  }
}

void BodySpaceDelassus::extract(const int* blocks, int count, BodySpaceDelassus& out,
                                std::vector<int>& localOf) const {
  gather(blocks, count, out);
  localOf.assign(static_cast<std::size_t>(bodies_), -1);
  int local = 0;
  for (int i = 0; i < count; ++i)  // bodies numbered in the order the blocks first meet them
    for (int side = 0; side < 2; ++side) {
      int& body = out.body_[2 * i + side];
      if (body < 0) continue;
      int& mapped = localOf[static_cast<std::size_t>(body)];
      if (mapped < 0) mapped = local++;
      body = mapped;
    }
  out.bodies_ = local;
}

void BodySpaceDelassus::setSide(int block, int side, int body,
                                const Eigen::Ref<const Eigen::MatrixXd>& J,
                                const Eigen::Ref<const Eigen::MatrixXd>& G) {
  const int k = size_.at(block);
  if (side < 0 || side > 1 || body < 0 || body >= bodies_ || J.rows() != k || J.cols() != 6 ||
      G.rows() != 6 || G.cols() != k)
    throw std::invalid_argument("BodySpaceDelassus::setSide: bad side, body or shapes");
  for (int a = 0; a < k; ++a) {
    const int row = offset_[block] + a;
    for (int c = 0; c < 6; ++c) {
      j_[(2 * row + side) * 6 + c] = J(a, c);
      g_[(2 * row + side) * 6 + c] = G(c, a);
    }
  }
  finitenessKnown_ = false;
  body_[2 * block + side] = body;
  entriesValid_ = false;
  diagonal_.clear();
  couplings_.clear();
}

void BodySpaceDelassus::setSide(int block, int side, int body, const double* J, const double* G) {
  if (block < 0 || block >= blockCount() || side < 0 || side > 1 || body < 0 || body >= bodies_)
    throw std::invalid_argument("BodySpaceDelassus::setSide: bad block, side or body");
  const int k = size_[block];
  finitenessKnown_ = false;
  body_[2 * block + side] = body;
  const auto first = static_cast<std::size_t>((2 * offset_[block] + side) * 6);
  double* j = j_.data() + first;
  double* g = g_.data() + first;
  for (int a = 0; a < k; ++a)      // row a of the block: 12 a further on (two sides per row)
    for (int c = 0; c < 6; ++c) {  // written out: six values, where a memcpy call costs more
      j[12 * a + c] = J[6 * a + c];
      g[12 * a + c] = G[6 * a + c];
    }
  entriesValid_ = false;
  diagonal_.clear();
  couplings_.clear();
}

void BodySpaceDelassus::bodyVelocities(const Eigen::VectorXd& x, Eigen::VectorXd& dv) const {
  dv.setZero(6 * bodies_);
  for (int b = 0; b < blockCount(); ++b) addBlockImpulse(b, x.data() + offset_[b], dv);
}

void BodySpaceDelassus::multiplyAdd(const Eigen::VectorXd& x, Eigen::VectorXd& y) const {
  Eigen::VectorXd& dv = productVelocities_;
  bodyVelocities(x, dv);
  addRowVelocities(dv, y.data());
}

void BodySpaceDelassus::diagonalBlock(int b, double* out) const {
  const int k = size_[b];
  std::copy_n(&diagonalBlocks()[9 * static_cast<std::size_t>(b)], k * k, out);
}

const std::vector<double>& BodySpaceDelassus::diagonalBlocks() const {
  if (diagonal_.empty() && blockCount() > 0) {
    diagonal_.assign(9 * size_.size(), 0.0);
    for (int b = 0; b < blockCount(); ++b) computeDiagonalBlock(b, &diagonal_[9 * b]);
  }
  return diagonal_;
}

const double* BodySpaceDelassus::sideCouplings(int b) const {
  if (couplings_.empty() && blockCount() > 0) {
    couplings_.assign(144 * size_.size(), 0.0);
    for (int block = 0; block < blockCount(); ++block) {
      if (size_[block] != 3) continue;
      const int row = offset_[block];
      for (int s = 0; s < 2; ++s)
        for (int t = 0; t < 2; ++t) {
          if (body_[2 * block + s] < 0 || body_[2 * block + t] < 0) continue;
          double* c = &couplings_[144 * static_cast<std::size_t>(block) + 36 * (2 * s + t)];
          for (int a = 0; a < 3; ++a) {  // sum over the rows of g_a j_a^T
            const double* g = G(row + a, s);
            const double* j = J(row + a, t);
            for (int col = 0; col < 6; ++col)
              for (int r = 0; r < 6; ++r) c[6 * col + r] += g[r] * j[col];
          }
        }
    }
  }
  return &couplings_[144 * static_cast<std::size_t>(b)];
}

void BodySpaceDelassus::computeDiagonalBlock(int b, double* out) const {
  const int k = size_[b];
  if (k == 3 && body_[2 * b] != body_[2 * b + 1]) {
    // A contact between two bodies (or one and a static one): W_bb = sum over sides of
    // J_s M_s^-1 J_s^T is symmetric (G = M^-1 J^T), so its upper triangle is summed and mirrored
    // (exactly symmetric; 12 products of six instead of 18).
    double w[6] = {0.0, 0.0, 0.0, 0.0, 0.0, 0.0};  // (0,0) (0,1) (0,2) (1,1) (1,2) (2,2)
    const int row = offset_[b];
    for (int side = 0; side < 2; ++side) {
      if (body_[2 * b + side] < 0) continue;
      const double *j0 = J(row, side), *j1 = J(row + 1, side), *j2 = J(row + 2, side);
      const double *g0 = G(row, side), *g1 = G(row + 1, side), *g2 = G(row + 2, side);
      w[0] += dot6(j0, g0);
      w[1] += dot6(j0, g1);
      w[2] += dot6(j0, g2);
      w[3] += dot6(j1, g1);
      w[4] += dot6(j1, g2);
      w[5] += dot6(j2, g2);
    }
    out[0] = w[0], out[1] = out[3] = w[1], out[2] = out[6] = w[2];
    out[4] = w[3], out[5] = out[7] = w[4], out[8] = w[5];
    return;
  }
  std::fill(out, out + k * k, 0.0);
  for (int side = 0; side < 2; ++side) {
    const int body = body_[2 * b + side];
    if (body < 0) continue;
    for (int other = 0; other < 2; ++other) {  // both sides on one body: both terms
      if (body_[2 * b + other] != body) continue;
      for (int a = 0; a < k; ++a)
        for (int c = 0; c < k; ++c)
          out[a * k + c] += dot6(J(offset_[b] + a, side), G(offset_[b] + c, other));
    }
  }
}

BodySpaceDelassus BodySpaceDelassus::selectRows(const std::vector<int>& rows) const {
  BodySpaceDelassus out(bodies_, std::vector<int>(rows.size(), 1));
  for (std::size_t k = 0; k < rows.size(); ++k) {
    const int row = rows[k];
    if (row < 0 || row >= size())
      throw std::invalid_argument("BodySpaceDelassus::selectRows: row out of range");
    const auto b = static_cast<std::size_t>(std::upper_bound(offset_.begin(), offset_.end(), row) -
                                            offset_.begin() - 1);
    for (int side = 0; side < 2; ++side) {
      out.body_[2 * k + side] = body_[2 * b + side];
      std::copy_n(J(row, side), 6, &out.j_[(2 * k + side) * 6]);
      std::copy_n(G(row, side), 6, &out.g_[(2 * k + side) * 6]);
    }
  }
  out.finitenessKnown_ = false;  // the selected rows may leave out non-finite values
  return out;
}

bool BodySpaceDelassus::allFinite() const {
  if (finitenessKnown_) return finite_;
  // x * 0 is 0 for finite x and NaN for inf or NaN: a pass without a branch per number, in four
  // independent sums. A block with both sides set is one contiguous run of J and of G.
  double s[4] = {0.0, 0.0, 0.0, 0.0};
  auto add = [&s](const double* values, int count) {  // count: a multiple of 6
    for (int i = 0; i < count; i += 6) {
      s[0] += values[i] * 0.0 + values[i + 4] * 0.0;
      s[1] += values[i + 1] * 0.0 + values[i + 5] * 0.0;
      s[2] += values[i + 2] * 0.0;
      s[3] += values[i + 3] * 0.0;
    }
  };
  for (int b = 0; b < blockCount(); ++b) {
    const bool both = body_[2 * b] >= 0 && body_[2 * b + 1] >= 0;
    if (both) {
      add(J(offset_[b], 0), 12 * size_[b]);
      add(G(offset_[b], 0), 12 * size_[b]);
      continue;
    }
    for (int side = 0; side < 2; ++side) {
      if (body_[2 * b + side] < 0) continue;
      for (int a = 0; a < size_[b]; ++a) {
        add(J(offset_[b] + a, side), 6);
        add(G(offset_[b] + a, side), 6);
      }
    }
  }
  finite_ = (s[0] + s[1]) + (s[2] + s[3]) == 0.0;
  finitenessKnown_ = true;
  return finite_;
}

const BlockSparseMatrix& BodySpaceDelassus::toBlockSparse() const {
  if (entriesValid_) return entries_;
  CsrScratch& w = csr_;
  // The pattern and its products depend only on the partition and on which body each side acts
  // on: kept from the last call when those are unchanged (a resting stack, a joint island), so
  // that only the values are recomputed, with the same sums in the same order.
  if (!(w.patternValid && w.keyBodies == bodies_ && w.keySize == size_ && w.keyBody == body_))
    buildPattern();
  w.values.resize(w.termStart.size() - 1);
  for (std::size_t e = 0; e + 1 < w.termStart.size(); ++e) {
    double value = 0.0;
    for (int t = w.termStart[e]; t < w.termStart[e + 1]; ++t)
      value += dot6(&j_[w.terms[t].first], &g_[w.terms[t].second]);
    w.values[e] = value;
  }
  entries_.adoptBlockCsr(size_, w.rowStart, w.columns, w.values);
  entriesValid_ = true;
  return entries_;
}

void BodySpaceDelassus::buildPattern() const {
  CsrScratch& w = csr_;
  // Blocks on each body, ascending (each block at most once per body), as CSR over bodies.
  w.bodyStart.assign(bodies_ + 1, 0);
  for (int b = 0; b < blockCount(); ++b)
    for (int side = 0; side < 2; ++side) {
      const int body = body_[2 * b + side];
      if (body >= 0 && !(side == 1 && body_[2 * b] == body)) ++w.bodyStart[body + 1];
    }
  for (int body = 0; body < bodies_; ++body) w.bodyStart[body + 1] += w.bodyStart[body];
  w.bodyBlocks.resize(w.bodyStart.back());
  w.next.assign(w.bodyStart.begin(), w.bodyStart.end() - 1);
  for (int b = 0; b < blockCount(); ++b)
    for (int side = 0; side < 2; ++side) {
      const int body = body_[2 * b + side];
      if (body >= 0 && !(side == 1 && body_[2 * b] == body)) w.bodyBlocks[w.next[body]++] = b;
    }
  // Entry (a, c) of block (b, j) = sum over the side pairs (s, t) on one body, in (s, t) order,
  // of J(row a of b, s) . G(column c of j, t): the terms, as offsets into j_ and g_.
  w.rowStart.assign(1, 0);
  w.columns.clear();
  w.termStart.assign(1, 0);
  w.terms.clear();
  for (int b = 0; b < blockCount(); ++b) {
    w.candidates.assign(1, b);  // the diagonal block is always stored
    for (int side = 0; side < 2; ++side) {
      const int body = body_[2 * b + side];
      if (body >= 0)
        w.candidates.insert(w.candidates.end(), w.bodyBlocks.begin() + w.bodyStart[body],
                            w.bodyBlocks.begin() + w.bodyStart[body + 1]);
    }
    std::sort(w.candidates.begin(), w.candidates.end());
    w.candidates.erase(std::unique(w.candidates.begin(), w.candidates.end()), w.candidates.end());
    for (const int j : w.candidates) {
      w.columns.push_back(j);
      for (int a = 0; a < size_[b]; ++a)
        for (int c = 0; c < size_[j]; ++c) {
          for (int s = 0; s < 2; ++s)
            for (int t = 0; t < 2; ++t)
              if (body_[2 * b + s] >= 0 && body_[2 * b + s] == body_[2 * j + t])
                w.terms.emplace_back((2 * (offset_[b] + a) + s) * 6,
                                     (2 * (offset_[j] + c) + t) * 6);
          w.termStart.push_back(static_cast<int>(w.terms.size()));
        }
    }
    w.rowStart.push_back(static_cast<int>(w.columns.size()));
  }
  w.keyBodies = bodies_;
  w.keySize = size_;
  w.keyBody = body_;
  w.patternValid = true;
}

}  // namespace coulomb::solvers
