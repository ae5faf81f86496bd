#include "ProblemCapture.hpp"

#include <coulomb/solvers/BlockSparseMatrix.hpp>
#include <coulomb/solvers/io/Fc3dText.hpp>

#include <fstream>
#include <system_error>
#include <utility>
#include <vector>

#include "Commands.hpp"

namespace coulomb::cli {

std::optional<solvers::ContactProblem> asPureContactProblem(
    const solvers::ContactProblem& problem) {
  bool padded = false;
  for (const solvers::ConstraintBlock& b : problem.blocks) {
    if (b.kind == solvers::BlockKind::Unilateral) {
      padded = true;
    } else if (!b.isContact() || b.anisotropic) {
      return std::nullopt;
    }
  }
  if (!padded) return problem;
  const std::vector<int> sizes = problem.blockSizes();
  const solvers::BlockSparseMatrix W = problem.W.toBlockSparse(sizes);
  const int blocks = static_cast<int>(sizes.size());
  // Padded unknown of each original scalar: a unilateral row becomes the normal of its contact.
  auto paddedRow = [&](int block, int row) { return 3 * block + row; };
  std::vector<solvers::MatrixBlockEntry> entries;
  for (int i = 0; i < blocks; ++i) {
    for (int k = W.rowBegin(i); k < W.rowEnd(i); ++k) {
      const int j = W.blockColumn(k);
      solvers::MatrixBlockEntry entry{i, j, std::vector<double>(9, 0.0)};
      for (int r = 0; r < sizes[i]; ++r)
        for (int c = 0; c < sizes[j]; ++c)
          entry.values[3 * r + c] = W.blockValues(k)[r * sizes[j] + c];
      if (i == j && sizes[i] == 1) entry.values[4] = entry.values[8] = 1.0;  // dummy tangents
      entries.push_back(std::move(entry));
    }
  }
  Eigen::VectorXd q = Eigen::VectorXd::Zero(3 * blocks);
  std::vector<double> mu(static_cast<std::size_t>(blocks), 0.0);
  const std::vector<int> offsets = problem.blockOffsets();
  for (int i = 0; i < blocks; ++i) {
    for (int r = 0; r < sizes[i]; ++r) q[paddedRow(i, r)] = problem.q[offsets[i] + r];
    if (problem.blocks[static_cast<std::size_t>(i)].isContact())
      mu[static_cast<std::size_t>(i)] = problem.blocks[static_cast<std::size_t>(i)].mu;
  }
  return solvers::ContactProblem::contacts(
      solvers::DelassusOperator::blockSparse(solvers::BlockSparseMatrix(
          std::vector<int>(static_cast<std::size_t>(blocks), 3), std::move(entries))),
      std::move(q), mu, problem.name);
}

ProblemCapture::ProblemCapture(std::filesystem::path directory, std::string sceneName,
                               std::optional<std::uint64_t> onlyStep)
    : directory_(std::move(directory)), sceneName_(std::move(sceneName)), onlyStep_(onlyStep) {
  std::error_code error;
  std::filesystem::create_directories(directory_, error);
  if (error || !std::filesystem::is_directory(directory_))
    throw CommandError("--capture: cannot create the folder '" + directory_.string() +
                       "': " + (error ? error.message() : "not a folder"));
}

void ProblemCapture::attach(engine::World& world) {
  world.setProblemObserver(
      [this, &world](std::int32_t island, const solvers::ContactProblem& problem) {
        capture(world.stepCount(), island, problem);
      });
}

void ProblemCapture::capture(std::uint64_t step, std::int32_t island,
                             const solvers::ContactProblem& problem) {
  if (onlyStep_ && *onlyStep_ != step) return;
  if (!failure_.empty()) return;
  std::optional<solvers::ContactProblem> pure = asPureContactProblem(problem);
  if (!pure) {
    ++islandsSkipped_;
    return;
  }
  const std::string name =
      sceneName_ + "_step" + std::to_string(step) + "_island" + std::to_string(island);
  pure->name = name;
  // The warm start the step's solve began from, beside the problem (`coulomb solve --start`), so
  // a replay can start where the simulation did; padded problems have no start of their size.
  if (problem.warmStart && problem.warmStart->size() == pure->q.size()) {
    const std::filesystem::path startPath = directory_ / (name + ".start");
    std::ofstream start(startPath);
    solvers::writeVector(*problem.warmStart, start);
    if (!start) {
      failure_ = "--capture: cannot write '" + startPath.string() + "'";
      return;
    }
  }
  pure->warmStart.reset();
  const std::filesystem::path path = directory_ / (name + ".fc3d");
  std::ofstream out(path);
  if (!out) {
    failure_ = "--capture: cannot write '" + path.string() + "'";
    return;
  }
  const std::string error = solvers::writeFc3dText(*pure, out, "coulomb-capture");
  if (!error.empty() || !out) {
    failure_ = "--capture: '" + path.string() + "': " + (error.empty() ? "write failed" : error);
    return;
  }
  ++filesWritten_;
}

void ProblemCapture::throwIfFailed() const {
  if (!failure_.empty()) throw CommandError(failure_);
}

}  // namespace coulomb::cli
