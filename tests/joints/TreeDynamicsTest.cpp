// ABA (Featherstone 2008 Table 7.1) against CRBA + RNEA (Tables 6.2, 5.1) on random trees:
// M(q) qdd + h(q, qd) = tau must hold to round-off for every joint type, fixed and floating base.
#include <gtest/gtest.h>
#include <coulomb/joints/tree/TreeDynamics.hpp>
#include <coulomb/joints/tree/TreeKinematics.hpp>

#include "RandomTrees.hpp"

#include <stdexcept>

using namespace coulomb::joints::tree;
using coulomb::geometry::Vector6d;
using randomtree::RandomSource;
using randomtree::RandomTreeOptions;

namespace {
double scaleOf(const Eigen::VectorXd& a, const Eigen::VectorXd& b, const Eigen::VectorXd& c) {
  return std::max(
      {1.0, a.lpNorm<Eigen::Infinity>(), b.lpNorm<Eigen::Infinity>(), c.lpNorm<Eigen::Infinity>()});
}

void expectAbaMatchesCrbaAndRnea(const RandomTreeOptions& options, unsigned seed) {
  RandomSource random(seed);
  const Articulation tree = randomtree::randomTree(random, options);
  const Eigen::VectorXd q = randomtree::randomConfiguration(tree, random);
  const Eigen::VectorXd qd = randomtree::randomVector(tree.nv(), random, 2.0);
  const Eigen::VectorXd tau = randomtree::randomVector(tree.nv(), random, 5.0);

  const Eigen::VectorXd qdd = forwardDynamics(tree, q, qd, tau);
  const Eigen::MatrixXd mass = massMatrix(tree, q);
  const Eigen::VectorXd bias = biasForces(tree, q, qd);
  const Eigen::VectorXd massTimesQdd = mass * qdd;
  const double scale = scaleOf(tau, bias, massTimesQdd);
  EXPECT_LE((massTimesQdd + bias - tau).lpNorm<Eigen::Infinity>(), 1e-12 * scale)
      << "seed " << seed << ", " << tree.linkCount() << " links";
  // RNEA of ABA's answer gives tau back.
  EXPECT_LE((inverseDynamics(tree, q, qd, qdd) - tau).lpNorm<Eigen::Infinity>(), 1e-12 * scale)
      << "seed " << seed;
  // M is symmetric positive definite.
  EXPECT_LE((mass - mass.transpose()).lpNorm<Eigen::Infinity>(), 1e-14 * mass.norm());
  EXPECT_EQ(Eigen::LLT<Eigen::MatrixXd>(mass).info(), Eigen::Success);
}
}  // namespace

TEST(TreeDynamics, AbaMatchesCrbaPlusRneaOnFixedBaseTrees) {
  for (unsigned seed = 1; seed <= 40; ++seed)
    expectAbaMatchesCrbaAndRnea({static_cast<int>(1 + seed % 15), false, true}, seed);
}

TEST(TreeDynamics, AbaMatchesCrbaPlusRneaOnFloatingBaseTrees) {
  for (unsigned seed = 100; seed <= 140; ++seed)
    expectAbaMatchesCrbaAndRnea({static_cast<int>(1 + seed % 15), true, true}, seed);
}

TEST(TreeDynamics, KineticEnergyIsHalfQdMQd) {
  RandomSource random(7);
  const Articulation tree = randomtree::randomTree(random, {12, true, true});
  const Eigen::VectorXd q = randomtree::randomConfiguration(tree, random);
  const Eigen::VectorXd qd = randomtree::randomVector(tree.nv(), random, 2.0);
  const double energy = kineticEnergy(tree, forwardKinematics(tree, q), qd);
  EXPECT_NEAR(energy, 0.5 * qd.dot(massMatrix(tree, q) * qd), 1e-12 * energy);
}

TEST(TreeDynamics, ExternalWrenchActsLikeJacobianTransposeTorque) {
  // A world force F at a point on a link is the generalised force J^T F (principle of virtual
  // power); ABA with the wrench and ABA with tau + J^T F must agree.
  RandomSource random(11);
  const Articulation tree = randomtree::randomTree(random, {9, true, true});
  const Eigen::VectorXd q = randomtree::randomConfiguration(tree, random);
  const Eigen::VectorXd qd = randomtree::randomVector(tree.nv(), random, 1.0);
  const Eigen::VectorXd tau = randomtree::randomVector(tree.nv(), random, 1.0);
  const TreeKinematics kin = forwardKinematics(tree, q);
  const int link = 7;
  const Eigen::Vector3d point = kin.worldPoses[link].apply(Eigen::Vector3d(0.1, -0.2, 0.3));
  const Eigen::Vector3d force(3.0, -1.0, 2.0);
  std::vector<Vector6d> wrenches(tree.linkCount(), Vector6d::Zero());
  wrenches[link] = linkWrenchFromPointForce(kin, link, point, force);
  const Eigen::VectorXd withWrench = forwardDynamics(tree, q, qd, tau, wrenches);
  const Eigen::VectorXd withTorque =
      forwardDynamics(tree, q, qd, tau + pointJacobian(tree, kin, link, point).transpose() * force);
  EXPECT_LE((withWrench - withTorque).lpNorm<Eigen::Infinity>(),
            1e-12 * std::max(1.0, withTorque.lpNorm<Eigen::Infinity>()));
  EXPECT_LE((inverseDynamics(tree, q, qd, withWrench, wrenches) - tau).lpNorm<Eigen::Infinity>(),
            1e-11);
}

TEST(TreeDynamics, FreeBodyFallsWithGravity) {
  // A single floating body: qdd = body-frame acceleration of its origin; with the COM at the
  // origin and no spin it is R^T g.
  coulomb::geometry::SpatialInertia inertia;
  inertia.mass = 2.0;
  inertia.inertiaAboutCom = Eigen::Vector3d(0.1, 0.2, 0.25).asDiagonal();
  const Articulation body({{"body", -1, TreeJoint::floating("free"), inertia}});
  Eigen::VectorXd q(7);
  const Eigen::Quaterniond r(Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()));
  q << 1.0, 2.0, 3.0, r.w(), r.x(), r.y(), r.z();
  const Eigen::VectorXd qdd =
      forwardDynamics(body, q, Eigen::VectorXd::Zero(6), Eigen::VectorXd::Zero(6));
  EXPECT_LE(qdd.head<3>().norm(), 1e-15);
  EXPECT_LE((qdd.tail<3>() - r.conjugate() * Eigen::Vector3d(0, 0, -9.81)).norm(), 1e-14);
}

TEST(TreeDynamics, MasslessSubtreeBehindAJointIsAClearError) {
  TreeLink base{"base", -1, TreeJoint::revolute("hinge", {}, Eigen::Vector3d::UnitZ()), {}};
  const Articulation tree({base});
  try {
    forwardDynamics(tree, Eigen::VectorXd::Zero(1), Eigen::VectorXd::Zero(1),
                    Eigen::VectorXd::Zero(1));
    FAIL() << "expected std::domain_error";
  } catch (const std::domain_error& e) {
    EXPECT_NE(std::string(e.what()).find("hinge"), std::string::npos) << e.what();
  }
  // Armature alone makes it well posed: qdd = tau / armature.
  base.joint.armature = 0.5;
  const Articulation withArmature({base});
  EXPECT_DOUBLE_EQ(forwardDynamics(withArmature, Eigen::VectorXd::Zero(1), Eigen::VectorXd::Zero(1),
                                   Eigen::VectorXd::Ones(1))(0),
                   2.0);
}

TEST(TreeDynamics, BadInputsNameTheJoint) {
  RandomSource random(3);
  const Articulation tree = randomtree::randomTree(random, {5, true, false});
  const Eigen::VectorXd q = tree.neutralConfiguration();
  Eigen::VectorXd qd = Eigen::VectorXd::Zero(tree.nv());
  EXPECT_THROW(forwardDynamics(tree, q, qd, Eigen::VectorXd::Zero(tree.nv() + 1)),
               std::invalid_argument);
  qd(2) = std::nan("");
  try {
    forwardDynamics(tree, q, qd, Eigen::VectorXd::Zero(tree.nv()));
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("joint0"), std::string::npos) << e.what();
  }
  Eigen::VectorXd zeroQuaternion = q;
  zeroQuaternion.segment<4>(3).setZero();
  EXPECT_THROW(forwardKinematics(tree, zeroQuaternion), std::invalid_argument);
}
