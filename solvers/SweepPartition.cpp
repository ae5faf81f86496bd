#include <coulomb/solvers/SweepPartition.hpp>

#include <coulomb/solvers/BodySpaceDelassus.hpp>

#include <algorithm>
#include <bit>
#include <cstddef>

namespace coulomb::solvers {

namespace {

// The part of the n-th node reached by the breadth-first search: equal counts per part.
int partOfRank(int rank, int nodes, int parts) {
  return static_cast<int>(static_cast<std::int64_t>(rank) * parts / nodes);
}

// Breadth first from the lowest unreached node, so that consecutive ranks are neighbours in
// space; nodePart[x] = the part of x's rank. neighbours(x, reach) calls reach(y) for each
// neighbour y of x.
template <class Neighbours>
void breadthFirstParts(int nodes, int parts, std::vector<int>& nodePart, std::vector<int>& queue,
                       Neighbours&& neighbours) {
  nodePart.assign(nodes, -1);
  queue.resize(nodes);
  int reached = 0, head = 0;
  auto reach = [&](int y) {
    if (nodePart[y] >= 0) return;
    nodePart[y] = partOfRank(reached, nodes, parts);
    queue[reached++] = y;
  };
  for (int start = 0; start < nodes; ++start) {
    reach(start);
    while (head < reached) neighbours(queue[head++], reach);
  }
}

}  // namespace

void SweepPartition::build(const PreparedProblem& problem, int parts) {
  const int blocks = problem.blockCount();
  parts = std::max(parts, 1);
  part_.assign(blocks, 0);
  colour_.assign(blocks, -1);
  if (parts > 1 && problem.bodySpace) {
    splitBodies(*problem.bodySpace, parts);
    colourBoundaryBodySpace(*problem.bodySpace);
  } else if (parts > 1) {
    splitBlocks(problem.W(), parts);
    colourBoundaryBlocks(problem.W());
  }
  fillOrder(parts);
}

void SweepPartition::splitBodies(const BodySpaceDelassus& body, int parts) {
  const int blocks = body.blockCount(), bodies = body.bodyCount();
  if (bodies == 0) return;
  nodeStart_.assign(bodies + 1, 0);  // the blocks of each body, ascending
  for (int b = 0; b < blocks; ++b)
    for (int side = 0; side < 2; ++side)
      if (const int k = body.blockBody(b, side); k >= 0) ++nodeStart_[k + 1];
  for (int k = 0; k < bodies; ++k) nodeStart_[k + 1] += nodeStart_[k];
  nodeBlocks_.resize(nodeStart_[bodies]);
  mark_.assign(nodeStart_.begin(), nodeStart_.end() - 1);
  for (int b = 0; b < blocks; ++b)
    for (int side = 0; side < 2; ++side)
      if (const int k = body.blockBody(b, side); k >= 0) nodeBlocks_[mark_[k]++] = b;
  breadthFirstParts(bodies, parts, nodePart_, queue_, [&](int x, auto&& reach) {
    for (int i = nodeStart_[x]; i < nodeStart_[x + 1]; ++i)
      for (int side = 0; side < 2; ++side)
        if (const int y = body.blockBody(nodeBlocks_[i], side); y >= 0) reach(y);
  });
  for (int b = 0; b < blocks; ++b) {
    const int a = body.blockBody(b, 0), c = body.blockBody(b, 1);
    if (a >= 0 && c >= 0)
      part_[b] = nodePart_[a] == nodePart_[c] ? nodePart_[a] : -1;
    else if (a >= 0 || c >= 0)
      part_[b] = nodePart_[a >= 0 ? a : c];
  }
}

void SweepPartition::splitBlocks(const BlockSparseMatrix& W, int parts) {
  const int blocks = W.blockCount();
  if (blocks == 0) return;
  breadthFirstParts(blocks, parts, nodePart_, queue_, [&](int x, auto&& reach) {
    for (int k = W.rowBegin(x); k < W.rowEnd(x); ++k) reach(W.blockColumn(k));
  });
  for (int b = 0; b < blocks; ++b) {
    part_[b] = nodePart_[b];
    for (int k = W.rowBegin(b); k < W.rowEnd(b); ++k)
      if (nodePart_[W.blockColumn(k)] != nodePart_[b]) {
        part_[b] = -1;
        break;
      }
  }
}

void SweepPartition::colourBoundaryBodySpace(const BodySpaceDelassus& body) {
  // One bit per colour used on each body; a boundary block takes the first colour free on both.
  const int blocks = body.blockCount(), bodies = body.bodyCount();
  mark_.assign(bodies, 0);  // boundary blocks per body
  for (int b = 0; b < blocks; ++b)
    if (part_[b] < 0)
      for (int side = 0; side < 2; ++side)
        if (const int k = body.blockBody(b, side); k >= 0) ++mark_[k];
  const int maxDegree = bodies == 0 ? 0 : *std::max_element(mark_.begin(), mark_.end());
  const int words = std::max(1, (2 * maxDegree + 63) / 64);  // first fit needs < 2 maxDegree
  used_.assign(static_cast<std::size_t>(bodies) * words, 0);
  for (int b = 0; b < blocks; ++b) {
    if (part_[b] >= 0) continue;
    const int first = body.blockBody(b, 0), second = body.blockBody(b, 1);
    std::uint64_t* a = first >= 0 ? &used_[static_cast<std::size_t>(first) * words] : nullptr;
    std::uint64_t* c = second >= 0 ? &used_[static_cast<std::size_t>(second) * words] : nullptr;
    int colour = 0;
    for (int w = 0; w < words; ++w) {
      const std::uint64_t taken = (a ? a[w] : 0) | (c ? c[w] : 0);
      if (taken != ~std::uint64_t{0}) {
        colour = 64 * w + std::countr_one(taken);
        break;
      }
    }
    colour_[b] = colour;
    const std::uint64_t bit = std::uint64_t{1} << (colour % 64);
    if (a) a[colour / 64] |= bit;
    if (c) c[colour / 64] |= bit;
  }
}

void SweepPartition::colourBoundaryBlocks(const BlockSparseMatrix& W) {
  // First fit over the boundary blocks already coloured in b's block row (W is structurally
  // symmetric); interior neighbours run in the parts' phase, before.
  const int blocks = W.blockCount();
  mark_.clear();  // mark_[c] == b: colour c is taken by a neighbour of b
  for (int b = 0; b < blocks; ++b) {
    if (part_[b] >= 0) continue;
    for (int k = W.rowBegin(b); k < W.rowEnd(b); ++k)
      if (const int j = W.blockColumn(k); j < b && part_[j] < 0) mark_[colour_[j]] = b;
    int colour = 0;
    while (colour < static_cast<int>(mark_.size()) && mark_[colour] == b) ++colour;
    if (colour == static_cast<int>(mark_.size())) mark_.push_back(-1);
    colour_[b] = colour;
  }
}

void SweepPartition::fillOrder(int parts) {
  // Counting sort: parts' interiors first, then the boundary's colours, ascending inside each.
  const int blocks = static_cast<int>(part_.size());
  int colours = 0;
  for (int b = 0; b < blocks; ++b) colours = std::max(colours, colour_[b] + 1);
  partStart_.assign(parts + 1, 0);
  colourStart_.assign(colours + 1, 0);
  for (int b = 0; b < blocks; ++b) {
    if (part_[b] >= 0)
      ++partStart_[part_[b] + 1];
    else
      ++colourStart_[colour_[b] + 1];
  }
  for (int k = 0; k < parts; ++k) partStart_[k + 1] += partStart_[k];
  colourStart_[0] = partStart_[parts];
  for (int c = 0; c < colours; ++c) colourStart_[c + 1] += colourStart_[c];
  order_.resize(blocks);
  mark_.assign(partStart_.begin(), partStart_.end() - 1);
  mark_.insert(mark_.end(), colourStart_.begin(), colourStart_.end() - 1);
  for (int b = 0; b < blocks; ++b)
    order_[part_[b] >= 0 ? mark_[part_[b]]++ : mark_[parts + colour_[b]]++] = b;
}

}  // namespace coulomb::solvers
