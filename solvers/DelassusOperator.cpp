#include <coulomb/solvers/DelassusOperator.hpp>

#include <stdexcept>

namespace coulomb::solvers {

DelassusOperator::DelassusOperator() : dense_(std::make_shared<Eigen::MatrixXd>()) {}

DelassusOperator DelassusOperator::dense(Eigen::MatrixXd W) {
  DelassusOperator op;
  op.storage_ = Storage::Dense;
  op.dense_ = std::make_shared<const Eigen::MatrixXd>(std::move(W));
  return op;
}

DelassusOperator DelassusOperator::blockSparse(BlockSparseMatrix W) {
  DelassusOperator op;
  op.storage_ = Storage::BlockSparse;
  op.dense_.reset();
  op.sparse_ = std::make_shared<const BlockSparseMatrix>(std::move(W));
  return op;
}

DelassusOperator DelassusOperator::matrixFree(int size, Product product) {
  if (size < 0 || !product) throw std::invalid_argument("matrixFree: needs a size and a product");
  DelassusOperator op;
  op.storage_ = Storage::MatrixFree;
  op.dense_.reset();
  op.size_ = size;
  op.product_ = std::move(product);
  return op;
}

DelassusOperator DelassusOperator::bodySpace(std::shared_ptr<const BodySpaceDelassus> W) {
  if (!W) throw std::invalid_argument("bodySpace: needs the factors");
  DelassusOperator op;
  op.storage_ = Storage::BodySpace;
  op.dense_.reset();
  op.body_ = std::move(W);
  return op;
}

const BodySpaceDelassus* DelassusOperator::bodySpaceOperator() const {
  return storage_ == Storage::BodySpace ? body_.get() : nullptr;
}

int DelassusOperator::rows() const {
  switch (storage_) {
    case Storage::Dense:
      return static_cast<int>(dense_->rows());
    case Storage::BlockSparse:
      return sparse_->size();
    case Storage::BodySpace:
      return body_->size();
    case Storage::MatrixFree:
      return size_;
  }
  return 0;
}

int DelassusOperator::cols() const {
  return storage_ == Storage::Dense ? static_cast<int>(dense_->cols()) : rows();
}

const Eigen::MatrixXd* DelassusOperator::denseMatrix() const {
  return storage_ == Storage::Dense ? dense_.get() : nullptr;
}

const BlockSparseMatrix* DelassusOperator::blockSparseMatrix() const {
  return storage_ == Storage::BlockSparse ? sparse_.get() : nullptr;
}

void DelassusOperator::velocity(const Eigen::VectorXd& x, const Eigen::VectorXd& q,
                                Eigen::VectorXd& u) const {
  switch (storage_) {
    case Storage::Dense:
      u.noalias() = (*dense_) * x;
      u += q;
      return;
    case Storage::BlockSparse:
      u = q;
      sparse_->multiplyAdd(x, u);
      return;
    case Storage::BodySpace:
      u = q;
      body_->multiplyAdd(x, u);
      return;
    case Storage::MatrixFree:
      u.setZero(size_);
      product_(x, u);
      u += q;
      return;
  }
}

Eigen::VectorXd DelassusOperator::column(int j) const {
  switch (storage_) {
    case Storage::Dense:
      return dense_->col(j);
    case Storage::BlockSparse: {
      Eigen::VectorXd e = Eigen::VectorXd::Zero(rows()), y;
      e[j] = 1.0;
      sparse_->multiply(e, y);
      return y;
    }
    case Storage::BodySpace: {
      Eigen::VectorXd e = Eigen::VectorXd::Zero(rows()), y = Eigen::VectorXd::Zero(rows());
      e[j] = 1.0;
      body_->multiplyAdd(e, y);
      return y;
    }
    case Storage::MatrixFree: {
      Eigen::VectorXd e = Eigen::VectorXd::Zero(size_), y = Eigen::VectorXd::Zero(size_);
      e[j] = 1.0;
      product_(e, y);
      return y;
    }
  }
  return {};
}

BlockSparseMatrix DelassusOperator::toBlockSparse(const std::vector<int>& blockSizes) const {
  if (storage_ == Storage::BlockSparse && sparse_->blockSizes() == blockSizes) return *sparse_;
  if (storage_ == Storage::BodySpace && body_->blockSizes() == blockSizes)
    return body_->toBlockSparse();
  const int n = rows();
  Eigen::MatrixXd gathered;  // block-sparse with another partition, or matrix-free
  if (storage_ != Storage::Dense) {
    gathered.resize(n, n);
    for (int j = 0; j < n; ++j) gathered.col(j) = column(j);
  }
  const Eigen::MatrixXd& dense = storage_ == Storage::Dense ? *dense_ : gathered;
  const auto nb = static_cast<int>(blockSizes.size());
  std::vector<int> offset(nb + 1, 0);
  for (int b = 0; b < nb; ++b) offset[b + 1] = offset[b] + blockSizes[b];
  if (offset.back() != n || dense.cols() != n)
    throw std::invalid_argument("toBlockSparse: partition does not match the operator size");
  // Straight into block-CSR (columns ascending per row; zero off-diagonal blocks skipped).
  std::vector<int> rowStart(nb + 1, 0), columns;
  std::vector<double> values;
  columns.reserve(static_cast<std::size_t>(nb) * nb);
  values.reserve(static_cast<std::size_t>(n) * n);
  for (int i = 0; i < nb; ++i) {
    for (int j = 0; j < nb; ++j) {
      const auto blk = dense.block(offset[i], offset[j], blockSizes[i], blockSizes[j]);
      if (i != j && (blk.array() == 0.0).all()) continue;
      columns.push_back(j);
      for (int a = 0; a < blockSizes[i]; ++a)
        for (int c = 0; c < blockSizes[j]; ++c) values.push_back(blk(a, c));
    }
    rowStart[i + 1] = static_cast<int>(columns.size());
  }
  return BlockSparseMatrix::fromBlockCsr(blockSizes, std::move(rowStart), std::move(columns),
                                         std::move(values));
}

}  // namespace coulomb::solvers
