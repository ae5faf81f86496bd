#include <coulomb/solvers/ContactProblem.hpp>

#include <algorithm>
#include <cmath>
#include <sstream>

namespace coulomb::solvers {

const char* blockKindName(BlockKind kind) {
  switch (kind) {
    case BlockKind::Equality:
      return "equality";
    case BlockKind::Bounded:
      return "bounded";
    case BlockKind::Unilateral:
      return "unilateral";
    case BlockKind::Contact3D:
      return "contact";
  }
  return "?";
}

ContactProblem ContactProblem::contacts(DelassusOperator W, Eigen::VectorXd q,
                                        const std::vector<double>& mu, std::string name) {
  ContactProblem p;
  p.name = std::move(name);
  p.W = std::move(W);
  p.q = std::move(q);
  p.blocks.reserve(mu.size());
  for (double m : mu) p.blocks.push_back(ConstraintBlock::contact(m));
  return p;
}

int ContactProblem::size() const {
  int n = 0;
  for (const ConstraintBlock& b : blocks) n += b.size();
  return n;
}

int ContactProblem::contactCount() const {
  int n = 0;
  for (const ConstraintBlock& b : blocks) n += b.isContact() ? 1 : 0;
  return n;
}

std::vector<int> ContactProblem::blockSizes() const {
  std::vector<int> s;
  s.reserve(blocks.size());
  for (const ConstraintBlock& b : blocks) s.push_back(b.size());
  return s;
}

std::vector<int> ContactProblem::blockOffsets() const {
  std::vector<int> o(blocks.size() + 1, 0);
  for (size_t b = 0; b < blocks.size(); ++b) o[b + 1] = o[b] + blocks[b].size();
  return o;
}

namespace {

// A message from its parts: the stream is built only on the failure path (validate() runs on
// every solve of every step).
template <class... Parts>
std::string say(const Parts&... parts) {
  std::ostringstream s;
  (s << ... << parts);
  return s.str();
}

// Only on the failure path: validate() itself keeps no offset table (it runs on every solve).
std::string where(const std::vector<ConstraintBlock>& blocks, int row) {
  size_t b = 0;
  int first = 0;
  while (b + 1 < blocks.size() && first + blocks[b].size() <= row) first += blocks[b++].size();
  std::ostringstream s;
  s << "row " << row << " (block " << b << ", " << blockKindName(blocks[b].kind);
  if (blocks[b].isContact())
    s << " component "
      << "NTT"[row - first];
  s << ")";
  return s.str();
}

// Whether all `count` values are finite: x * 0 is 0 for finite x and NaN otherwise, so their sum
// is 0 exactly when all are; in any order, so Eigen sums them in packets (no chain of dependent
// adds). The search for the first bad entry is the caller's, only when one is bad.
bool allFinite(const double* v, std::size_t count) {
  return (Eigen::Map<const Eigen::ArrayXd>(v, static_cast<Eigen::Index>(count)) * 0.0).sum() == 0.0;
}

}  // namespace

std::optional<std::string> ContactProblem::validate() const {
  const int n = size();
  if (W.rows() != W.cols()) {
    return say("W is ", W.rows(), " x ", W.cols(), ", not square");
  }
  if (W.rows() != n) {
    return say("W is ", W.rows(), " x ", W.cols(), " but the blocks have ", n, " unknowns");
  }
  if (q.size() != n) {
    return say("q has ", q.size(), " entries, expected ", n);
  }
  if (warmStart && warmStart->size() != n) {
    return say("warm start has ", warmStart->size(), " entries, expected ", n);
  }
  auto samePartition = [&](const std::vector<int>& sizes) {
    if (sizes.size() != blocks.size()) return false;
    for (size_t b = 0; b < blocks.size(); ++b)
      if (sizes[b] != blocks[b].size()) return false;
    return true;
  };
  if (const BlockSparseMatrix* s = W.blockSparseMatrix(); s && !samePartition(s->blockSizes()))
    return std::string("the block partition of W differs from the problem's blocks");
  if (const BodySpaceDelassus* s = W.bodySpaceOperator(); s && !samePartition(s->blockSizes()))
    return std::string("the block partition of W differs from the problem's blocks");
  for (size_t b = 0; b < blocks.size(); ++b) {
    const ConstraintBlock& k = blocks[b];
    // Built only for a message: a stream per block made validate() a hot spot of every step.
    auto at = [&] {
      std::ostringstream name;
      name << "block " << b << " (" << blockKindName(k.kind) << ")";
      return name;
    };
    if (k.isContact()) {
      const double m[3] = {k.mu, k.mu1, k.mu2};
      const char* names[3] = {"mu", "mu1", "mu2"};
      for (int t = 0; t < 3; ++t) {
        if (t > 0 && !k.anisotropic) break;
        if (!std::isfinite(m[t])) return at().str() + ": " + names[t] + " is not finite";
        if (m[t] < 0) {
          return say(at().str(), ": ", names[t], " = ", m[t], " < 0");
        }
      }
    }
    if (k.kind == BlockKind::Bounded) {
      if (std::isnan(k.lower) || std::isnan(k.upper) || k.lower > k.upper) {
        return say(at().str(), ": bounds [", k.lower, ", ", k.upper, "] are not an interval");
      }
    }
  }
  // One branch-free pass each; the search for the first bad entry only when there is one.
  if (!allFinite(q.data(), static_cast<std::size_t>(n)))
    for (int i = 0; i < n; ++i)
      if (!std::isfinite(q[i])) return "q at " + where(blocks, i) + " is not finite";
  if (warmStart && !allFinite(warmStart->data(), static_cast<std::size_t>(n)))
    for (int i = 0; i < n; ++i)
      if (!std::isfinite((*warmStart)[i]))
        return "warm start at " + where(blocks, i) + " is not finite";
  // Entries of W: non-finite anywhere (stored), diagonal positive (>= 0 on a frictionless
  // tangent row). The test is a comparison per row; the message is built only for a bad one.
  auto diagonalFine = [&](size_t b, int a, double w) {
    if (w > 0) return true;
    const ConstraintBlock& k = blocks[b];
    return k.isContact() && a != 0 && (k.anisotropic ? (a == 1 ? k.mu1 : k.mu2) : k.mu) == 0.0 &&
           w >= 0;
  };
  // Row a of block b, whose first row is `first`.
  auto diagonalOkIn = [&](size_t b, int first, int a, double w) -> std::optional<std::string> {
    if (diagonalFine(b, a, w)) return std::nullopt;
    std::ostringstream s;
    s << "W diagonal at " << where(blocks, first + a) << " is " << w
      << ", must be positive (W block not positive on its diagonal)";
    return s.str();
  };
  // Every diagonal entry W_ii given by diagonalAt(i), block by block.
  auto diagonalOk = [&](auto diagonalAt) -> std::optional<std::string> {
    int first = 0;
    for (size_t b = 0; b < blocks.size(); first += blocks[b++].size())
      for (int a = 0; a < blocks[b].size(); ++a)
        if (auto e = diagonalOkIn(b, first, a, diagonalAt(first + a))) return e;
    return std::nullopt;
  };
  if (const Eigen::MatrixXd* d = W.denseMatrix()) {
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
        if (!std::isfinite((*d)(i, j))) {
          return say("W(", i, ", ", j, ") is not finite, at ", where(blocks, i));
        }
    if (auto e = diagonalOk([d](int i) { return (*d)(i, i); })) return e;
  } else if (const BlockSparseMatrix* s = W.blockSparseMatrix()) {
    // One branch-free pass over the stored values; the search only if bad.
    if (!allFinite(s->values().data(), s->values().size()))
      for (int b = 0; b < s->blockCount(); ++b)
        for (int k = s->rowBegin(b); k < s->rowEnd(b); ++k) {
          const int c = s->blockColumn(k), sb = s->blockSize(b), sc = s->blockSize(c);
          for (int t = 0; t < sb * sc; ++t)
            if (!std::isfinite(s->blockValues(k)[t])) {
              return say("W(", s->blockOffset(b) + t / sc, ", ", s->blockOffset(c) + t % sc,
                         ") is not finite, at ", where(blocks, s->blockOffset(b) + t / sc));
            }
        }
    for (int b = 0; b < s->blockCount(); ++b) {
      if (s->diagonalBlock(b) < 0) {
        return say("W has no diagonal block for block ", b);
      }
      const double* v = s->blockValues(s->diagonalBlock(b));
      for (int a = 0; a < s->blockSize(b); ++a) {
        const double w = v[(s->blockSize(b) + 1) * a];
        if (!diagonalFine(static_cast<size_t>(b), a, w))
          return diagonalOkIn(static_cast<size_t>(b), s->blockOffset(b), a, w);
      }
    }
  } else if (const BodySpaceDelassus* s = W.bodySpaceOperator()) {
    // O(rows), from the diagonal blocks the solvers compute anyway (the same partition as the
    // problem's blocks, checked above). Every number of the factors enters W's diagonal: J_s[a][c]
    // and G_s[a][c] meet in the term J_s[a][c] G_s[a][c] of W_aa, so an inf or NaN among them makes
    // W_aa inf or NaN; finite factors give a finite W (an overflow is caught here too).
    const std::vector<double>& d = s->diagonalBlocks();
    int first = 0;
    for (size_t b = 0; b < blocks.size(); first += blocks[b++].size()) {
      const int k = blocks[b].size();
      for (int a = 0; a < k; ++a) {
        const double w = d[9 * b + static_cast<size_t>((k + 1) * a)];
        if (std::isfinite(w) && diagonalFine(b, a, w)) continue;
        if (!std::isfinite(w))
          return say("W (body-space factors J, M^-1 J^T) is not finite: its diagonal at ",
                     where(blocks, first + a), " is ", w);
        return diagonalOkIn(b, first, a, w);
      }
    }
  } else {
    for (int i = 0; i < n; ++i) {
      const Eigen::VectorXd col = W.column(i);
      for (int r = 0; r < n; ++r)
        if (!std::isfinite(col[r])) {
          return say("W(", r, ", ", i, ") is not finite, at ", where(blocks, r));
        }
    }
    if (auto e = diagonalOk([this](int i) { return W.column(i)[i]; })) return e;
  }
  return std::nullopt;
}

}  // namespace coulomb::solvers
