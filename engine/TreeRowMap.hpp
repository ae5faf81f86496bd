#pragma once
// The trees one row set touches, in joint space: per tree the joint-space Jacobians of its row
// blocks (J_side * twistJacobian(link, proxy origin), docs/articulations.md) and its
// impulse-level ABA at the step's q. ArticulationStage::mapRows builds it once when the island is
// assembled (the trees' part of W needs it) and the impulses are applied through the same map:
// it belongs to the island (AssemblyScratch), not to the stage, so nothing carries over between
// islands and two islands never share one.
#include <coulomb/joints/tree/ArticulationImpulse.hpp>

#include <Eigen/Core>

#include <cstddef>
#include <cstdint>
#include <vector>

namespace coulomb::engine {

struct TreeRowMap {
  struct Tree {
    std::int32_t articulation = -1;
    joints::tree::ArticulationImpulse response;
    std::vector<int> blocks;                 // row blocks with a side on this tree
    std::vector<Eigen::MatrixXd> jacobians;  // first blocks.size(): k x nv (both sides)
    Eigen::VectorXd change;                  // M^-1 J_t^T lambda
  };
  std::vector<Tree> trees;  // the first `count` are this row set's (storage kept)
  std::size_t count = 0;
  // Scratch kept for its storage: tree index per articulation slot (-1: none), one row side's
  // twist Jacobian, M^-1 J_t^T per row block, one impulse-level column and joint impulse.
  std::vector<std::int32_t> treeIndex;
  Eigen::Matrix<double, 6, Eigen::Dynamic> twist;
  std::vector<Eigen::MatrixXd> minvJt;
  Eigen::VectorXd column, jointRow, jointTau;
};

}  // namespace coulomb::engine
