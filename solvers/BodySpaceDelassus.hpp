#pragma once
// W = J M^-1 J^T kept factored, as Bullet's sequential impulse keeps it (issue 7 item 11): per
// solver block (1 or 3 rows) its Jacobian on at most two bodies of the island, J_s (k x 6), and
// G_s = M_s^-1 J_s^T (6 x k). Nothing of size nnz(W) is formed: W x costs O(rows) through the body
// velocities dv = sum_s G_s x_s, u = J dv (docs/solver-derivations.md (1.1)), and a Gauss-Seidel
// step on block b reads u_b = q_b + J_b dv and moves dv by G_b (r_b' - r_b), O(1) per contact
// instead of one 3 x 3 product per contact sharing a body (~28 on a pyramid). Solvers that need W's
// entries (Newton, Lemke, staggered) get them from toBlockSparse(), built once on demand and
// cached.
#include <coulomb/solvers/BlockSparseMatrix.hpp>

#include <Eigen/Core>

#include <memory>
#include <utility>
#include <vector>

namespace coulomb::solvers {

class BodySpaceDelassus {
 public:
  /// `blockSizes`: the solver blocks (1 or 3 rows each); `bodyCount`: the island's dynamic bodies
  /// (local indices 0 .. bodyCount-1).
  BodySpaceDelassus(int bodyCount, std::vector<int> blockSizes);
  /// The same operator emptied (every side unset) for a new partition, keeping its storage.
  void reset(int bodyCount, const std::vector<int>& blockSizes);

  /// Side `side` (0 or 1) of block `block` acts on local body `body` with the block's rows `J`
  /// (k x 6, twist (v, w)) and `G` = M^-1 J^T (6 x k). A side left unset carries no unknowns.
  void setSide(int block, int side, int body, const Eigen::Ref<const Eigen::MatrixXd>& J,
               const Eigen::Ref<const Eigen::MatrixXd>& G);
  /// The same from raw storage, no temporaries (the assembler's hot path): `J` holds the k rows of
  /// 6 one after the other (row-major k x 6), `G` the k columns of 6 (column-major 6 x k).
  void setSide(int block, int side, int body, const double* J, const double* G);

  [[nodiscard]] int size() const { return offset_.back(); }
  [[nodiscard]] int blockCount() const { return static_cast<int>(size_.size()); }
  [[nodiscard]] int bodyCount() const { return bodies_; }
  [[nodiscard]] int blockSize(int b) const { return size_[b]; }
  [[nodiscard]] int blockOffset(int b) const { return offset_[b]; }
  [[nodiscard]] const std::vector<int>& blockSizes() const { return size_; }
  /// The local body side `side` (0 or 1) of block b acts on; -1 when that side has no unknowns.
  [[nodiscard]] int blockBody(int b, int side) const { return body_[2 * b + side]; }
  /// Row `row`'s Jacobian on side `side` and the same row's column of M^-1 J^T (6 numbers each:
  /// linear, angular); meaningless on a side left unset (blockBody < 0), which readers skip.
  [[nodiscard]] const double* jacobianRow(int row, int side) const { return J(row, side); }
  [[nodiscard]] const double* inverseMassColumn(int row, int side) const { return G(row, side); }

  /// dv = M^-1 J^T x (6 per body: linear, angular).
  void bodyVelocities(const Eigen::VectorXd& x, Eigen::VectorXd& dv) const;
  /// u_b = J_b dv for block b (adds to u[0 .. k-1]). Inline: the Gauss-Seidel inner loop.
  void addBlockVelocity(int b, const Eigen::VectorXd& dv, double* u) const {
    const int k = size_[b], row = offset_[b];
    for (int side = 0; side < 2; ++side) {
      const int body = body_[2 * b + side];
      if (body < 0) continue;
      const double* v = dv.data() + 6 * body;
      for (int a = 0; a < k; ++a) u[a] += dot6(J(row + a, side), v);
    }
  }
  /// u += J dv for every row (u: size() values), block by block as addBlockVelocity.
  void addRowVelocities(const Eigen::VectorXd& dv, double* u) const {
    for (int b = 0; b < blockCount(); ++b) addBlockVelocity(b, dv, u + offset_[b]);
  }
  /// dv += G_b dx for block b (dx: k values). Inline: the Gauss-Seidel inner loop.
  void addBlockImpulse(int b, const double* dx, Eigen::VectorXd& dv) const {
    const int k = size_[b], row = offset_[b];
    for (int side = 0; side < 2; ++side) {
      const int body = body_[2 * b + side];
      if (body < 0) continue;
      double* v = dv.data() + 6 * body;
      for (int a = 0; a < k; ++a) {
        const double* g = G(row + a, side);
        const double x = dx[a];
        for (int c = 0; c < 6; ++c) v[c] += g[c] * x;
      }
    }
  }
  /// y += W x, O(rows).
  void multiplyAdd(const Eigen::VectorXd& x, Eigen::VectorXd& y) const;
  /// W_bb, row-major k x k (sum over the block's sides).
  void diagonalBlock(int b, double* out) const;
  /// Every W_bb, row-major k x k at 9 b; computed once on the first call (validation, the
  /// chooser and the prepared problem all read them) and kept until a setSide.
  [[nodiscard]] const std::vector<double>& diagonalBlocks() const;
  /// Block b's couplings G_s J_t (s, t = 0, 1: 6 x 6 column-major at 36 (2 s + t)), the block's
  /// terms of M^-1 J^T J, for a 3-row block with both terms' sides set: the Newton step in body
  /// space adds them, over its shift, for every sticking contact (BodySpaceNewtonSolve). Computed
  /// for every block on the first call and kept until a side is set.
  [[nodiscard]] const double* sideCouplings(int b) const;
  /// The listed blocks, in that order, as an operator of their own on the same bodies: block i
  /// of `out` is block blocks[i] here (a sweep's blocks made contiguous in memory, so that a
  /// sweep in that order streams them). Reuses out's storage.
  void gather(const int* blocks, int count, BodySpaceDelassus& out) const;
  /// The same as gather, on the listed blocks' bodies only: those are renumbered 0 .. k-1 in the
  /// order the blocks first meet them (`localOf[body]`: the new number, or -1), so the operator
  /// has the velocities of a group of contacts and no more (solvers/ActiveGroups).
  void extract(const int* blocks, int count, BodySpaceDelassus& out,
               std::vector<int>& localOf) const;
  /// The operator of the given rows only (each a 1-row block on the same bodies), e.g. the
  /// contacts' normal rows for the split impulse: W' = W restricted to those rows and columns.
  [[nodiscard]] BodySpaceDelassus selectRows(const std::vector<int>& rows) const;
  /// Every number of the set sides finite (unset sides are not read): one pass over the set
  /// sides, kept until a side is set again. (validate() reads W's diagonal instead, which every
  /// number of the factors enters.)
  [[nodiscard]] bool allFinite() const;
  /// W with every nonzero block (k, j) of blocks sharing a body, cached after the first call.
  [[nodiscard]] const BlockSparseMatrix& toBlockSparse() const;

 private:
  static double dot6(const double* a, const double* b) {
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2] + a[3] * b[3] + a[4] * b[4] + a[5] * b[5];
  }
  [[nodiscard]] const double* J(int row, int side) const { return &j_[(2 * row + side) * 6]; }
  [[nodiscard]] const double* G(int row, int side) const { return &g_[(2 * row + side) * 6]; }
  void reset(int bodyCount);  // from size_
  void computeDiagonalBlock(int b, double* out) const;
  int bodies_ = 0;
  std::vector<int> size_, offset_;
  std::vector<int> body_;                 // 2 per block, -1 = no unknowns on that side
  std::vector<double> j_, g_;             // 2 x 6 per row: J_s row and G_s column of side s
  mutable bool finitenessKnown_ = false;  // allFinite()'s answer, until a side is set
  mutable bool finite_ = true;
  // toBlockSparse() cache and the lists it is built from, kept for their storage.
  struct CsrScratch {
    std::vector<int> bodyStart, bodyBlocks, next, rowStart, columns, candidates;
    std::vector<double> values;
    std::vector<int> termStart;              // per stored entry: its terms
    std::vector<std::pair<int, int>> terms;  // (offset in j_, offset in g_) per dot product
    int keyBodies = -1;                      // what the pattern was built for
    std::vector<int> keySize, keyBody;
    bool patternValid = false;
  };
  void buildPattern() const;  // csr_'s pattern and terms for the current partition and bodies
  mutable BlockSparseMatrix entries_;
  mutable bool entriesValid_ = false;
  mutable CsrScratch csr_;
  mutable std::vector<double> diagonal_;   // diagonalBlocks() cache, 9 per block
  mutable std::vector<double> couplings_;  // sideCouplings() cache, 144 per block
  // multiplyAdd's dv, kept for its storage: like the caches above, a const call writes it, so one
  // operator is not for two threads at once.
  mutable Eigen::VectorXd productVelocities_;
};

}  // namespace coulomb::solvers
