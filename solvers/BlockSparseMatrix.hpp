#pragma once
// Block-sparse square matrix over a partition of the unknowns into blocks of 1 or 3 rows
// (a scalar row or a contact (N, T1, T2)). Block rows are stored in order with their nonzero
// blocks sorted by column; each block is dense and row-major. For a pure contact problem this is
// the usual 3x3 block-CSR (BSR) layout of the fc3d format.
#include <Eigen/Core>
#include <Eigen/SparseCore>

#include <vector>

namespace coulomb::solvers {

struct MatrixBlockEntry {
  int row = 0;                 // block row
  int col = 0;                 // block column
  std::vector<double> values;  // rowSize x colSize, row-major
};

class BlockSparseMatrix {
 public:
  BlockSparseMatrix() = default;
  // Blocks with the same (row, col) are summed; the block sizes must be 1, 2 or 3.
  BlockSparseMatrix(std::vector<int> blockSizes, std::vector<MatrixBlockEntry> entries);
  // Directly from block-CSR arrays, without per-block allocations (the assembler's hot path):
  // block row b holds the blocks k in [rowStart[b], rowStart[b + 1]), columns blockColumns[k]
  // strictly increasing within a row, values concatenated block after block (each row-major,
  // blockSize(row) x blockSize(col)). Throws std::invalid_argument when the arrays disagree.
  static BlockSparseMatrix fromBlockCsr(std::vector<int> blockSizes, std::vector<int> rowStart,
                                        std::vector<int> blockColumns, std::vector<double> values);
  // W's blocks over the partition `blockSizes` (sum = W's size): exact zero off-diagonal blocks
  // dropped, diagonal blocks always kept. Reuses this matrix's storage.
  void assignFromDense(const Eigen::MatrixXd& W, const std::vector<int>& blockSizes);
  // The same into this matrix, copying the arrays into its own storage (no allocation once it
  // has held a matrix as large).
  void assignBlockCsr(const std::vector<int>& blockSizes, const std::vector<int>& rowStart,
                      const std::vector<int>& blockColumns, const std::vector<double>& values);
  // The same, taking `values` by swapping it with this matrix's (the caller gets the old storage
  // back, to refill next time): a fresh W's entries are not copied once more.
  void adoptBlockCsr(const std::vector<int>& blockSizes, const std::vector<int>& rowStart,
                     const std::vector<int>& blockColumns, std::vector<double>& values);

  [[nodiscard]] int blockCount() const { return static_cast<int>(blockSize_.size()); }
  [[nodiscard]] int size() const { return blockOffset_.empty() ? 0 : blockOffset_.back(); }
  [[nodiscard]] int blockSize(int b) const { return blockSize_[b]; }
  [[nodiscard]] int blockOffset(int b) const { return blockOffset_[b]; }
  [[nodiscard]] const std::vector<int>& blockSizes() const { return blockSize_; }
  [[nodiscard]] int nonZeroBlocks() const { return static_cast<int>(col_.size()); }
  [[nodiscard]] int nonZeros() const { return static_cast<int>(values_.size()); }

  // Stored blocks of block row b are k in [rowBegin(b), rowEnd(b)), column blockColumn(k).
  [[nodiscard]] int rowBegin(int b) const { return rowStart_[b]; }
  [[nodiscard]] int rowEnd(int b) const { return rowStart_[b + 1]; }
  [[nodiscard]] int blockColumn(int k) const { return col_[k]; }
  [[nodiscard]] const double* blockValues(int k) const { return values_.data() + valueStart_[k]; }
  [[nodiscard]] double* blockValues(int k) { return values_.data() + valueStart_[k]; }
  // Index k of the diagonal block (b, b), or -1 when it is not stored.
  [[nodiscard]] int diagonalBlock(int b) const { return diagonal_[b]; }
  [[nodiscard]] const std::vector<double>& values() const { return values_; }

  // y += A x, row by row, blocks in increasing column order, entries in increasing column order
  // (the summation order of fc3d_velocity, so u = q + W r is bit-identical to the reference).
  void multiplyAdd(const Eigen::VectorXd& x, Eigen::VectorXd& y) const;
  // y += A^T x
  void multiplyTransposeAdd(const Eigen::VectorXd& x, Eigen::VectorXd& y) const;
  // y = A x
  void multiply(const Eigen::VectorXd& x, Eigen::VectorXd& y) const;
  // A(i, j) for dense conversion and tests.
  [[nodiscard]] Eigen::MatrixXd toDense() const;
  [[nodiscard]] Eigen::SparseMatrix<double> toSparse() const;
  // D A D for a diagonal scaling D = diag(scale).
  [[nodiscard]] BlockSparseMatrix scaledSymmetric(const Eigen::VectorXd& scale) const;
  // Adds s to every diagonal entry (blocks (b, b) must be stored).
  void addToDiagonal(double s);
  /// The diagonal entries of `base` + s written over this matrix's, whose other entries and
  /// structure are base's (a copy of base, shifted before): the same numbers as a new copy of
  /// base with addToDiagonal(s), without copying the off-diagonal blocks again.
  void assignShiftedDiagonal(const BlockSparseMatrix& base, double s);

 private:
  void indexBlockCsr();  // offsets, value starts and diagonal from the CSR arrays; validates
  // The block-CSR pattern (sizes, row starts, columns) copied into this matrix's storage.
  void assignPattern(const std::vector<int>& blockSizes, const std::vector<int>& rowStart,
                     const std::vector<int>& blockColumns);
  std::vector<int> blockSize_, blockOffset_;
  std::vector<int> rowStart_, col_, valueStart_, diagonal_;
  std::vector<double> values_;
};

}  // namespace coulomb::solvers
