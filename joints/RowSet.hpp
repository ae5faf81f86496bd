#pragma once
// The rows of one island: every block of every joint and contact, in emission order (joints by
// id, then contacts in manifold order), which is deterministic.
#include <coulomb/joints/RowBlock.hpp>

#include <vector>

namespace coulomb::joints {

struct RowSet {
  std::vector<RowBlock> blocks;

  [[nodiscard]] int rowCount() const {
    int n = 0;
    for (const RowBlock& b : blocks) n += b.rows();
    return n;
  }
};

}  // namespace coulomb::joints
