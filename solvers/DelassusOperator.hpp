#pragma once
// The Delassus operator W of a contact problem (u = W r + q, docs/solver-derivations.md (1.1))
// behind one type: dense, block-sparse (blocks of 1 or 3 rows, see BlockSparseMatrix), body-space
// (J and M^-1 J^T per block, see BodySpaceDelassus: what the engine gives large islands) or
// matrix-free (a function computing W x). Solvers that need entries ask for toBlockSparse(); for a
// matrix-free operator that costs one product per unknown, for a body-space one O(nnz W) once
// (cached).
#include <coulomb/solvers/BlockSparseMatrix.hpp>
#include <coulomb/solvers/BodySpaceDelassus.hpp>

#include <Eigen/Core>

#include <functional>
#include <memory>

namespace coulomb::solvers {

class DelassusOperator {
 public:
  enum class Storage { Dense, BlockSparse, BodySpace, MatrixFree };
  // y = W x; y has the right size on entry.
  using Product = std::function<void(const Eigen::VectorXd& x, Eigen::VectorXd& y)>;

  DelassusOperator();  // empty 0 x 0 (dense); allocates nothing
  static DelassusOperator dense(Eigen::MatrixXd W);
  static DelassusOperator blockSparse(BlockSparseMatrix W);
  // Sharing storage the caller may refill once no operator holds it any more (the assembler's
  // buffers, reused from step to step).
  static DelassusOperator dense(std::shared_ptr<const Eigen::MatrixXd> W);
  static DelassusOperator blockSparse(std::shared_ptr<const BlockSparseMatrix> W);
  static DelassusOperator matrixFree(int size, Product product);
  static DelassusOperator bodySpace(std::shared_ptr<const BodySpaceDelassus> W);

  [[nodiscard]] Storage storage() const { return storage_; }
  [[nodiscard]] int rows() const;
  [[nodiscard]] int cols() const;
  [[nodiscard]] const Eigen::MatrixXd* denseMatrix() const;
  [[nodiscard]] const BlockSparseMatrix* blockSparseMatrix() const;
  [[nodiscard]] const BodySpaceDelassus* bodySpaceOperator() const;
  // The shared body-space factors (same lifetime as any copy of this operator), or null.
  [[nodiscard]] std::shared_ptr<const BodySpaceDelassus> sharedBodySpace() const { return body_; }
  [[nodiscard]] std::shared_ptr<const BlockSparseMatrix> sharedBlockSparse() const {
    return sparse_;
  }

  // u = W x + q. For block-sparse storage the summation order is that of fc3d_velocity.
  void velocity(const Eigen::VectorXd& x, const Eigen::VectorXd& q, Eigen::VectorXd& u) const;
  // W restricted to the partition `blockSizes` (sum = rows()); exact zero blocks are dropped,
  // diagonal blocks always kept.
  [[nodiscard]] BlockSparseMatrix toBlockSparse(const std::vector<int>& blockSizes) const;
  // The same into `out`, reusing its storage (dense, block-sparse and body-space storage).
  void toBlockSparse(const std::vector<int>& blockSizes, BlockSparseMatrix& out) const;
  // Column j of W (dense: a copy; block-sparse: gathered; matrix-free: one product).
  [[nodiscard]] Eigen::VectorXd column(int j) const;

 private:
  Storage storage_ = Storage::Dense;
  std::shared_ptr<const Eigen::MatrixXd> dense_;  // shared: problems are copied cheaply
  std::shared_ptr<const BlockSparseMatrix> sparse_;
  std::shared_ptr<const BodySpaceDelassus> body_;
  int size_ = 0;
  Product product_;
};

}  // namespace coulomb::solvers
