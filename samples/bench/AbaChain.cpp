#include "AbaChain.hpp"

#include <coulomb/joints/tree/TreeDynamics.hpp>

#include <cmath>
#include <string>
#include <vector>

namespace coulomb::samples {

using joints::tree::Articulation;
using joints::tree::TreeJoint;
using joints::tree::TreeLink;

Articulation serialChain(int n) {
  std::vector<TreeLink> links;
  const geometry::SpatialInertia box{1.0, Eigen::Vector3d(0.05, 0, 0),
                                     Eigen::Vector3d(0.002, 0.01, 0.01).asDiagonal()};
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector3d axis = i % 2 == 0 ? Eigen::Vector3d::UnitY() : Eigen::Vector3d::UnitX();
    links.push_back(
        {"link" + std::to_string(i), i - 1,
         TreeJoint::revolute("joint" + std::to_string(i),
                             geometry::Pose::translation({i == 0 ? 0.0 : 0.1, 0, 0}), axis),
         box});
  }
  return Articulation(links);
}

Eigen::VectorXd wave(int n, double phase) {
  Eigen::VectorXd v(n);
  for (int i = 0; i < n; ++i) v(i) = 0.5 * std::sin(phase + 0.7 * i);
  return v;
}

double abaResidual(const Articulation& tree) {
  const Eigen::VectorXd q = wave(tree.nq(), 0.1), qd = wave(tree.nv(), 0.2),
                        tau = wave(tree.nv(), 0.3);
  const Eigen::VectorXd qdd = joints::tree::forwardDynamics(tree, q, qd, tau);
  return (joints::tree::massMatrix(tree, q) * qdd + joints::tree::biasForces(tree, q, qd) - tau)
      .lpNorm<Eigen::Infinity>();
}

}  // namespace coulomb::samples
