#pragma once
// The visit order of a Gauss-Seidel sweep split so that its work can run on several threads with
// the bits of the serial sweep (docs/solvers.md "Parallel sweeps"). The problem's bodies (blocks,
// for an entry-wise W) are split into parts of consecutive breadth-first order, so that each part
// is a connected, compact region; a block whose bodies all lie in one part is that part's
// interior, any other is on the boundary. Interiors of different parts share no body (W_bc = 0),
// so the parts run at once, each in ascending block order (the order and memory locality of the
// unsplit sweep); the boundary blocks follow, coloured so that no two of a colour share a body
// (first fit, as Box2D v3's constraint graph colouring), colour after colour. The split depends
// on the problem and the number of parts alone, never on the threads.
#include <coulomb/solvers/PreparedProblem.hpp>

#include <algorithm>
#include <cstdint>
#include <vector>

namespace coulomb::solvers {

class SweepPartition {
 public:
  /// The most parts a sweep is split into (SolverOptions::sweepPartBlocks): enough for 64
  /// threads; a larger problem gets larger parts.
  static constexpr int kMaxParts = 64;
  /// The parts of a problem of `blocks` blocks for SolverOptions::sweepPartBlocks (1: unsplit).
  [[nodiscard]] static int partsFor(int blocks, int partBlocks) {
    return partBlocks > 0 ? std::clamp(blocks / partBlocks, 1, kMaxParts) : 1;
  }

  /// Splits the blocks of `problem` into `parts` parts (>= 1; 1 gives the block order with no
  /// boundary). Reuses this object's storage.
  void build(const PreparedProblem& problem, int parts);

  /// Interior blocks part by part, then boundary blocks colour by colour.
  [[nodiscard]] const std::vector<int>& order() const { return order_; }
  [[nodiscard]] int parts() const { return static_cast<int>(partStart_.size()) - 1; }
  /// order()[partStart(k) .. partStart(k + 1)): the interior of part k, ascending.
  [[nodiscard]] int partStart(int part) const { return partStart_[part]; }
  [[nodiscard]] int colours() const { return static_cast<int>(colourStart_.size()) - 1; }
  /// order()[colourStart(c) .. colourStart(c + 1)): boundary blocks of colour c, ascending;
  /// colourStart(0) == partStart(parts()).
  [[nodiscard]] int colourStart(int colour) const { return colourStart_[colour]; }
  /// The part of an interior block, -1 for a boundary block.
  [[nodiscard]] int partOf(int block) const { return part_[block]; }
  /// The colour of a boundary block, -1 for an interior block.
  [[nodiscard]] int colourOf(int block) const { return colour_[block]; }

 private:
  void splitBodies(const BodySpaceDelassus& body, int parts);
  void splitBlocks(const BlockSparseMatrix& W, int parts);
  void colourBoundaryBodySpace(const BodySpaceDelassus& body);
  void colourBoundaryBlocks(const BlockSparseMatrix& W);
  void fillOrder(int parts);
  std::vector<int> part_, colour_, order_, partStart_, colourStart_;
  // scratch
  std::vector<int> nodeStart_, nodeBlocks_, queue_, nodePart_, mark_;
  std::vector<std::uint64_t> used_;
};

}  // namespace coulomb::solvers
