#pragma once
// The rows of one island: every block of every row source (joints, contacts, trees), each
// source's blocks contiguous and named by a BlockRange, in a deterministic order.
#include <coulomb/joints/RowBlock.hpp>

#include <cstddef>
#include <span>
#include <vector>

namespace coulomb::joints {

/// The blocks one row source appended to a RowSet: [first, first + count).
struct BlockRange {
  std::size_t first = 0;
  std::size_t count = 0;
  [[nodiscard]] std::size_t end() const { return first + count; }
};

struct RowSet {
  std::vector<RowBlock> blocks;

  [[nodiscard]] int rowCount() const {
    int n = 0;
    for (const RowBlock& b : blocks) n += b.rows();
    return n;
  }
  [[nodiscard]] std::span<const RowBlock> in(BlockRange range) const {
    return std::span<const RowBlock>(blocks).subspan(range.first, range.count);
  }
};

}  // namespace coulomb::joints
