#include "entries/FuzzEntries.hpp"
#include "entries/SolveAll.hpp"

#include <coulomb/solvers/ContactProblem.hpp>

#include <Eigen/Core>

#include <array>
#include <cmath>
#include <limits>

namespace coulomb::fuzz {
namespace {

// Reads the fuzz input front to back; past its end every byte is 0 (inputs of any length decode).
class ByteReader {
 public:
  ByteReader(const std::uint8_t* data, std::size_t size) : data_(data), size_(size) {}
  std::uint8_t byte() { return pos_ < size_ ? data_[pos_++] : 0; }
  // One byte picks a special value (zeros, extremes, non-finite) 1 time in 8, else two more bytes
  // give a moderate number in [-32, 32) with 1/1024 resolution.
  double number() {
    static constexpr double inf = std::numeric_limits<double>::infinity();
    static constexpr double nan = std::numeric_limits<double>::quiet_NaN();
    // clang-format off
    static constexpr std::array<double, 16> special = {
        0.0, -0.0, 1.0, -1.0, 1e-12, 1e12, 1e-300, 1e300, inf, -inf, nan, 5e-324, 0.5, 2.0, 1e-6, 1e6};
    // clang-format on
    const std::uint8_t b = byte();
    if (b < 32) return special[b % special.size()];
    const std::uint8_t high = byte();  // two statements: the order of the reads is fixed
    const std::uint8_t low = byte();
    const auto raw = static_cast<std::int16_t>(static_cast<std::uint16_t>(high << 8 | low));
    return raw / 1024.0;
  }

 private:
  const std::uint8_t* data_;
  std::size_t size_;
  std::size_t pos_ = 0;
};

constexpr int kMaxBlocks = 6;  // at most 18 unknowns: every solver runs in well under a millisecond

solvers::ConstraintBlock decodeBlock(ByteReader& in) {
  using solvers::ConstraintBlock;
  switch (in.byte() % 8) {
    case 4: {  // arguments in separate statements: their order of evaluation is unspecified
      const double mu1 = in.number();
      return ConstraintBlock::anisotropicContact(mu1, in.number());
    }
    case 5:
      return ConstraintBlock::equality();
    case 6: {
      const double lo = in.number();
      return ConstraintBlock::bounded(lo, in.number());
    }
    case 7:
      return ConstraintBlock::unilateral();
    default:
      return ConstraintBlock::contact(in.number());
  }
}

}  // namespace

// Layout: [block count] [flags] [iteration cap] [block kinds and coefficients]
// [W: J entries (+ diagonal shift) or raw entries] [q] [warm start when flagged].
std::string solversEntry(const std::uint8_t* data, std::size_t size) {
  ByteReader in(data, size);
  const int blockCount = 1 + in.byte() % kMaxBlocks;
  const std::uint8_t flags = in.byte();
  const int maxIterations = 1 + in.byte() % 30;
  solvers::ContactProblem problem;
  problem.name = "fuzz";
  for (int b = 0; b < blockCount; ++b) problem.blocks.push_back(decodeBlock(in));
  const int n = problem.size();
  Eigen::MatrixXd W(n, n);
  if (flags & 1) {  // raw entries: possibly asymmetric, indefinite or non-finite
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) W(i, j) = in.number();
  } else {  // W = J J^T + shift I: symmetric positive semi-definite, like an assembled Delassus
    Eigen::MatrixXd J(n, n);
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) J(i, j) = in.number();
    W = J * J.transpose();
    W.diagonal().array() += std::abs(in.number());
  }
  problem.q.resize(n);
  for (int i = 0; i < n; ++i) problem.q[i] = in.number();
  if (flags & 2) {
    Eigen::VectorXd start(n);
    for (int i = 0; i < n; ++i) start[i] = in.number();
    problem.warmStart = start;
  }
  switch ((flags >> 2) % 3) {  // every storage of DelassusOperator
    case 0:
      problem.W = solvers::DelassusOperator::dense(W);
      break;
    case 1: {
      const solvers::DelassusOperator dense = solvers::DelassusOperator::dense(W);
      problem.W = solvers::DelassusOperator::blockSparse(dense.toBlockSparse(problem.blockSizes()));
      break;
    }
    default:
      problem.W = solvers::DelassusOperator::matrixFree(
          n, [W](const Eigen::VectorXd& x, Eigen::VectorXd& y) { y.noalias() = W * x; });
  }
  return solveWithEverySolver(problem, maxIterations);
}

}  // namespace coulomb::fuzz
