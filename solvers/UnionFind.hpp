#pragma once
// A disjoint-set forest over 0 .. n-1 (path halving). The smaller index of two joined roots
// becomes the root, so every root is its set's smallest member whatever the order of the unions:
// numberings made from roots (islands, groups) do not depend on the order edges are met in.
// Shared by the island builder, the contact groups and the joint-loop test.
#include <numeric>
#include <utility>
#include <vector>

namespace coulomb::solvers {

class UnionFind {
 public:
  /// n singletons, reusing the storage.
  void reset(int n) {
    parent_.resize(static_cast<std::size_t>(n));
    std::iota(parent_.begin(), parent_.end(), 0);
  }
  [[nodiscard]] int find(int x) {
    while (parent_[x] != x) x = parent_[x] = parent_[parent_[x]];
    return x;
  }
  /// Joins the sets of a and b; false when they were one set already.
  bool unite(int a, int b) {
    a = find(a);
    b = find(b);
    if (a == b) return false;
    if (b < a) std::swap(a, b);
    parent_[b] = a;
    return true;
  }

 private:
  std::vector<int> parent_;
};

}  // namespace coulomb::solvers
