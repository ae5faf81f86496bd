#include <coulomb/solvers/BlockSparseMatrix.hpp>

#include <algorithm>
#include <stdexcept>
#include <string>

namespace coulomb::solvers {

BlockSparseMatrix::BlockSparseMatrix(std::vector<int> blockSizes,
                                     std::vector<MatrixBlockEntry> entries)
    : blockSize_(std::move(blockSizes)) {
  const int nb = blockCount();
  blockOffset_.assign(nb + 1, 0);
  for (int b = 0; b < nb; ++b) {
    if (blockSize_[b] < 1 || blockSize_[b] > 3)
      throw std::invalid_argument("block " + std::to_string(b) + " has size " +
                                  std::to_string(blockSize_[b]) + ", expected 1, 2 or 3");
    blockOffset_[b + 1] = blockOffset_[b] + blockSize_[b];
  }
  for (const MatrixBlockEntry& e : entries) {
    if (e.row < 0 || e.row >= nb || e.col < 0 || e.col >= nb)
      throw std::invalid_argument("block (" + std::to_string(e.row) + ", " + std::to_string(e.col) +
                                  ") outside " + std::to_string(nb) + " blocks");
    if (static_cast<int>(e.values.size()) != blockSize_[e.row] * blockSize_[e.col])
      throw std::invalid_argument("block (" + std::to_string(e.row) + ", " + std::to_string(e.col) +
                                  ") has " + std::to_string(e.values.size()) + " values");
  }
  std::vector<int> order(entries.size());
  for (size_t k = 0; k < order.size(); ++k) order[k] = static_cast<int>(k);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
    return entries[a].row != entries[b].row ? entries[a].row < entries[b].row
                                            : entries[a].col < entries[b].col;
  });
  rowStart_.assign(nb + 1, 0);
  diagonal_.assign(nb, -1);
  for (size_t idx = 0; idx < order.size(); ++idx) {
    const MatrixBlockEntry& e = entries[order[idx]];
    const bool same = !col_.empty() && idx > 0 && entries[order[idx - 1]].row == e.row &&
                      entries[order[idx - 1]].col == e.col;
    if (same) {  // duplicate block: sum
      double* v = values_.data() + valueStart_.back();
      for (size_t t = 0; t < e.values.size(); ++t) v[t] += e.values[t];
      continue;
    }
    col_.push_back(e.col);
    valueStart_.push_back(static_cast<int>(values_.size()));
    values_.insert(values_.end(), e.values.begin(), e.values.end());
    ++rowStart_[e.row + 1];
    if (e.row == e.col) diagonal_[e.row] = static_cast<int>(col_.size()) - 1;
  }
  for (int b = 0; b < nb; ++b) rowStart_[b + 1] += rowStart_[b];
}

BlockSparseMatrix BlockSparseMatrix::fromBlockCsr(std::vector<int> blockSizes,
                                                  std::vector<int> rowStart,
                                                  std::vector<int> blockColumns,
                                                  std::vector<double> values) {
  BlockSparseMatrix m;
  m.blockSize_ = std::move(blockSizes);
  m.rowStart_ = std::move(rowStart);
  m.col_ = std::move(blockColumns);
  m.values_ = std::move(values);
  m.indexBlockCsr();
  return m;
}

void BlockSparseMatrix::assignPattern(const std::vector<int>& blockSizes,
                                      const std::vector<int>& rowStart,
                                      const std::vector<int>& blockColumns) {
  blockSize_.assign(blockSizes.begin(), blockSizes.end());
  rowStart_.assign(rowStart.begin(), rowStart.end());
  col_.assign(blockColumns.begin(), blockColumns.end());
}

void BlockSparseMatrix::assignBlockCsr(const std::vector<int>& blockSizes,
                                       const std::vector<int>& rowStart,
                                       const std::vector<int>& blockColumns,
                                       const std::vector<double>& values) {
  assignPattern(blockSizes, rowStart, blockColumns);
  values_.assign(values.begin(), values.end());
  indexBlockCsr();
}

void BlockSparseMatrix::adoptBlockCsr(const std::vector<int>& blockSizes,
                                      const std::vector<int>& rowStart,
                                      const std::vector<int>& blockColumns,
                                      std::vector<double>& values) {
  // The pattern this matrix already holds and has indexed (an island refilled step after step
  // with the same contacts): only the values change. Checking it is three comparisons of the
  // index arrays, against re-checking and re-indexing every block (a fifth of a small island's
  // assembly).
  const bool indexed = blockOffset_.size() == blockSize_.size() + 1;
  const bool samePattern = indexed && blockSize_ == blockSizes && rowStart_ == rowStart &&
                           col_ == blockColumns && values.size() == values_.size();
  values_.swap(values);
  if (samePattern) return;
  assignPattern(blockSizes, rowStart, blockColumns);
  try {
    indexBlockCsr();
  } catch (...) {
    blockOffset_.clear();  // not indexed: the same pattern given again is checked again
    throw;
  }
}

void BlockSparseMatrix::assignFromDense(const Eigen::MatrixXd& W,
                                        const std::vector<int>& blockSizes) {
  const auto nb = static_cast<int>(blockSizes.size());
  blockSize_.assign(blockSizes.begin(), blockSizes.end());
  blockOffset_.assign(nb + 1, 0);
  for (int b = 0; b < nb; ++b) blockOffset_[b + 1] = blockOffset_[b] + blockSizes[b];
  if (blockOffset_.back() != W.rows() || W.cols() != W.rows())
    throw std::invalid_argument("toBlockSparse: partition does not match the operator size");
  // Straight into block-CSR (columns ascending per row; zero off-diagonal blocks skipped).
  rowStart_.assign(nb + 1, 0);
  col_.clear();
  values_.clear();
  for (int i = 0; i < nb; ++i) {
    for (int j = 0; j < nb; ++j) {
      const auto blk = W.block(blockOffset_[i], blockOffset_[j], blockSizes[i], blockSizes[j]);
      if (i != j && (blk.array() == 0.0).all()) continue;
      col_.push_back(j);
      for (int a = 0; a < blockSizes[i]; ++a)
        for (int c = 0; c < blockSizes[j]; ++c) values_.push_back(blk(a, c));
    }
    rowStart_[i + 1] = static_cast<int>(col_.size());
  }
  indexBlockCsr();
}

void BlockSparseMatrix::indexBlockCsr() {
  const int nb = blockCount();
  blockOffset_.assign(nb + 1, 0);
  for (int b = 0; b < nb; ++b) {
    if (blockSize_[b] < 1 || blockSize_[b] > 3)
      throw std::invalid_argument("block " + std::to_string(b) + " has size " +
                                  std::to_string(blockSize_[b]) + ", expected 1, 2 or 3");
    blockOffset_[b + 1] = blockOffset_[b] + blockSize_[b];
  }
  const auto nnzBlocks = static_cast<int>(col_.size());
  if (static_cast<int>(rowStart_.size()) != nb + 1 || rowStart_.front() != 0 ||
      rowStart_.back() != nnzBlocks)
    throw std::invalid_argument("fromBlockCsr: row starts do not match the block columns");
  valueStart_.resize(nnzBlocks);
  diagonal_.assign(nb, -1);
  int valueCount = 0;
  for (int b = 0; b < nb; ++b) {
    if (rowStart_[b + 1] < rowStart_[b])
      throw std::invalid_argument("fromBlockCsr: row starts decrease");
    for (int k = rowStart_[b]; k < rowStart_[b + 1]; ++k) {
      const int c = col_[k];
      if (c < 0 || c >= nb || (k > rowStart_[b] && c <= col_[k - 1]))
        throw std::invalid_argument("fromBlockCsr: block columns of row " + std::to_string(b) +
                                    " are not strictly increasing inside [0, " +
                                    std::to_string(nb) + ")");
      if (c == b) diagonal_[b] = k;
      valueStart_[k] = valueCount;
      valueCount += blockSize_[b] * blockSize_[c];
    }
  }
  if (valueCount != static_cast<int>(values_.size()))
    throw std::invalid_argument("fromBlockCsr: " + std::to_string(values_.size()) +
                                " values, the blocks need " + std::to_string(valueCount));
}

void BlockSparseMatrix::multiplyAdd(const Eigen::VectorXd& x, Eigen::VectorXd& y) const {
  // A block row's sums kept in registers (y written once per row, not once per product, which
  // also frees the compiler from assuming y aliases the values); contact rows are 3 x 3. The
  // terms are added one by one into y's value in column order: the same sums, bit for bit, as
  // the plain row-by-row product (the common residual is checked bit-identical to Siconos').
  const double* xs = x.data();
  double* ys = y.data();
  const int nb = blockCount();
  for (int i = 0; i < nb; ++i) {
    const int ri = blockOffset_[i], si = blockSize_[i];
    if (si == 3) {
      double y0 = ys[ri], y1 = ys[ri + 1], y2 = ys[ri + 2];
      for (int k = rowStart_[i]; k < rowStart_[i + 1]; ++k) {
        const int sj = blockSize_[col_[k]];
        const double* v = values_.data() + valueStart_[k];
        const double* xj = xs + blockOffset_[col_[k]];
        if (sj == 3) {  // contact by contact, written out: the same terms in the same order
          y0 += v[0] * xj[0];
          y1 += v[3] * xj[0];
          y2 += v[6] * xj[0];
          y0 += v[1] * xj[1];
          y1 += v[4] * xj[1];
          y2 += v[7] * xj[1];
          y0 += v[2] * xj[2];
          y1 += v[5] * xj[2];
          y2 += v[8] * xj[2];
          continue;
        }
        for (int c = 0; c < sj; ++c) {
          y0 += v[c] * xj[c];
          y1 += v[sj + c] * xj[c];
          y2 += v[2 * sj + c] * xj[c];
        }
      }
      ys[ri] = y0;
      ys[ri + 1] = y1;
      ys[ri + 2] = y2;
      continue;
    }
    for (int a = 0; a < si; ++a) {
      double sum = ys[ri + a];
      for (int k = rowStart_[i]; k < rowStart_[i + 1]; ++k) {
        const int cj = blockOffset_[col_[k]], sj = blockSize_[col_[k]];
        const double* v = values_.data() + valueStart_[k] + sj * a;
        for (int c = 0; c < sj; ++c) sum += v[c] * xs[cj + c];
      }
      ys[ri + a] = sum;
    }
  }
}

void BlockSparseMatrix::multiplyTransposeAdd(const Eigen::VectorXd& x, Eigen::VectorXd& y) const {
  for (int i = 0; i < blockCount(); ++i) {
    const int ri = blockOffset_[i], si = blockSize_[i];
    for (int k = rowStart_[i]; k < rowStart_[i + 1]; ++k) {
      const int cj = blockOffset_[col_[k]], sj = blockSize_[col_[k]];
      const double* v = values_.data() + valueStart_[k];
      for (int a = 0; a < si; ++a)
        for (int c = 0; c < sj; ++c) y[cj + c] += v[sj * a + c] * x[ri + a];
    }
  }
}

void BlockSparseMatrix::multiply(const Eigen::VectorXd& x, Eigen::VectorXd& y) const {
  y.setZero(size());
  multiplyAdd(x, y);
}

Eigen::MatrixXd BlockSparseMatrix::toDense() const {
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(size(), size());
  for (int i = 0; i < blockCount(); ++i)
    for (int k = rowStart_[i]; k < rowStart_[i + 1]; ++k) {
      const int j = col_[k], sj = blockSize_[j];
      for (int a = 0; a < blockSize_[i]; ++a)
        for (int c = 0; c < sj; ++c)
          A(blockOffset_[i] + a, blockOffset_[j] + c) = values_[valueStart_[k] + sj * a + c];
    }
  return A;
}

Eigen::SparseMatrix<double> BlockSparseMatrix::toSparse() const {
  std::vector<Eigen::Triplet<double>> t;
  t.reserve(values_.size());
  for (int i = 0; i < blockCount(); ++i)
    for (int k = rowStart_[i]; k < rowStart_[i + 1]; ++k) {
      const int j = col_[k], sj = blockSize_[j];
      for (int a = 0; a < blockSize_[i]; ++a)
        for (int c = 0; c < sj; ++c)
          t.emplace_back(blockOffset_[i] + a, blockOffset_[j] + c,
                         values_[valueStart_[k] + sj * a + c]);
    }
  Eigen::SparseMatrix<double> A(size(), size());
  A.setFromTriplets(t.begin(), t.end());
  return A;
}

BlockSparseMatrix BlockSparseMatrix::scaledSymmetric(const Eigen::VectorXd& scale) const {
  BlockSparseMatrix out = *this;
  for (int i = 0; i < blockCount(); ++i)
    for (int k = rowStart_[i]; k < rowStart_[i + 1]; ++k) {
      const int j = col_[k], sj = blockSize_[j];
      double* v = out.values_.data() + valueStart_[k];
      for (int a = 0; a < blockSize_[i]; ++a)
        for (int c = 0; c < sj; ++c)
          v[sj * a + c] *= scale[blockOffset_[i] + a] * scale[blockOffset_[j] + c];
    }
  return out;
}

void BlockSparseMatrix::assignShiftedDiagonal(const BlockSparseMatrix& base, double s) {
  if (base.blockCount() != blockCount() || base.values_.size() != values_.size() ||
      base.diagonal_ != diagonal_)
    throw std::logic_error("assignShiftedDiagonal: not the base matrix's structure");
  for (int b = 0; b < blockCount(); ++b) {
    if (diagonal_[b] < 0) throw std::logic_error("assignShiftedDiagonal: missing diagonal block");
    const auto first = static_cast<std::size_t>(valueStart_[diagonal_[b]]);
    for (int a = 0; a < blockSize_[b]; ++a) {
      const std::size_t at = first + static_cast<std::size_t>((blockSize_[b] + 1) * a);
      values_[at] = base.values_[at] + s;
    }
  }
}

void BlockSparseMatrix::addToDiagonal(double s) {
  for (int b = 0; b < blockCount(); ++b) {
    if (diagonal_[b] < 0) throw std::logic_error("addToDiagonal: missing diagonal block");
    double* v = values_.data() + valueStart_[diagonal_[b]];
    for (int a = 0; a < blockSize_[b]; ++a) v[(blockSize_[b] + 1) * a] += s;
  }
}

}  // namespace coulomb::solvers
