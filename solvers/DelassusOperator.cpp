#include <coulomb/solvers/DelassusOperator.hpp>

#include <stdexcept>

namespace coulomb::solvers {

namespace {
// The 0 x 0 matrix every empty operator shares (immutable), so that default construction, which
// every problem and every step does, never allocates.
const std::shared_ptr<const Eigen::MatrixXd>& emptyMatrix() {
  static const auto empty = std::make_shared<const Eigen::MatrixXd>();
  return empty;
}
}  // namespace

DelassusOperator::DelassusOperator() : dense_(emptyMatrix()) {}

DelassusOperator DelassusOperator::dense(Eigen::MatrixXd W) {
  return dense(std::make_shared<const Eigen::MatrixXd>(std::move(W)));
}

DelassusOperator DelassusOperator::dense(std::shared_ptr<const Eigen::MatrixXd> W) {
  if (!W) throw std::invalid_argument("dense: needs a matrix");
  DelassusOperator op;
  op.storage_ = Storage::Dense;
  op.dense_ = std::move(W);
  return op;
}

DelassusOperator DelassusOperator::blockSparse(BlockSparseMatrix W) {
  return blockSparse(std::make_shared<const BlockSparseMatrix>(std::move(W)));
}

DelassusOperator DelassusOperator::blockSparse(std::shared_ptr<const BlockSparseMatrix> W) {
  if (!W) throw std::invalid_argument("blockSparse: needs a matrix");
  DelassusOperator op;
  op.storage_ = Storage::BlockSparse;
  op.dense_.reset();
  op.sparse_ = std::move(W);
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
  BlockSparseMatrix out;
  toBlockSparse(blockSizes, out);
  return out;
}

void DelassusOperator::toBlockSparse(const std::vector<int>& blockSizes,
                                     BlockSparseMatrix& out) const {
  if (storage_ == Storage::BlockSparse && sparse_->blockSizes() == blockSizes) {
    out = *sparse_;
    return;
  }
  if (storage_ == Storage::BodySpace && body_->blockSizes() == blockSizes) {
    out = body_->toBlockSparse();
    return;
  }
  if (storage_ == Storage::Dense) {
    out.assignFromDense(*dense_, blockSizes);
    return;
  }
  const int n = rows();  // block-sparse with another partition, or matrix-free
  Eigen::MatrixXd gathered(n, n);
  for (int j = 0; j < n; ++j) gathered.col(j) = column(j);
  out.assignFromDense(gathered, blockSizes);
}

}  // namespace coulomb::solvers
