// ABA, CRBA and RNEA against DART 6.12's forward dynamics of real URDF robots (shared corpus,
// copied into tests/data/urdf with tests/data/urdf/ORIGIN.md): qdd to 1e-9 relative to max|qdd|,
// M and h to 1e-10 relative to their largest entry.
#include <gtest/gtest.h>
#include <coulomb/joints/tree/TreeDynamics.hpp>

#include <nlohmann/json.hpp>

#include <fstream>
#include <string>

using namespace coulomb::joints::tree;
using nlohmann::json;

namespace {
Eigen::Vector3d vector3(const json& j) {
  return {j[0].get<double>(), j[1].get<double>(), j[2].get<double>()};
}

TreeJoint jointOf(const json& j) {
  const json& w = j["quaternion_wxyz"];
  const coulomb::geometry::Pose origin{Eigen::Quaterniond(w[0].get<double>(), w[1].get<double>(),
                                                          w[2].get<double>(), w[3].get<double>())
                                           .normalized(),
                                       vector3(j["xyz"])};
  const std::string type = j["type"], name = j["name"];
  if (type == "revolute") return TreeJoint::revolute(name, origin, vector3(j["axis"]));
  if (type == "continuous") return TreeJoint::continuous(name, origin, vector3(j["axis"]));
  if (type == "prismatic") return TreeJoint::prismatic(name, origin, vector3(j["axis"]));
  if (type == "fixed") return TreeJoint::fixed(name, origin);
  throw std::runtime_error("unsupported joint type " + type);
}

struct Fixture {
  json data;
  std::vector<int> dofToV;  // reference DOF i -> our velocity index
};

Fixture load(const std::string& model) {
  const std::string path = std::string(COULOMB_TEST_DATA_DIR) + "/urdf/" + model + "/tree.json";
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot open " + path);
  Fixture f;
  f.data = json::parse(in);
  return f;
}

Articulation build(Fixture& fixture) {
  std::vector<TreeLink> links;
  for (const json& l : fixture.data["links"]) {
    coulomb::geometry::SpatialInertia inertia;
    inertia.mass = l["mass"];
    inertia.centerOfMass = vector3(l["com"]);
    const json& i = l["inertia_about_com"];  // Ixx, Iyy, Izz, Ixy, Ixz, Iyz
    inertia.inertiaAboutCom << i[0], i[3], i[4], i[3], i[1], i[5], i[4], i[5], i[2];
    links.push_back({l["name"], l["parent"], jointOf(l["joint"]), inertia});
  }
  Articulation tree(links, vector3(fixture.data["gravity"]));
  for (const json& name : fixture.data["dof_names"]) {
    int found = -1;
    for (int k = 0; k < tree.linkCount(); ++k)
      if (tree.link(k).joint.name == name.get<std::string>()) found = tree.vIndex(k);
    EXPECT_GE(found, 0) << name;
    fixture.dofToV.push_back(found);
  }
  return tree;
}

void expectMatchesReference(const std::string& model) {
  Fixture fixture = load(model);
  const Articulation tree = build(fixture);
  ASSERT_EQ(tree.nv(), static_cast<int>(fixture.dofToV.size()));
  ASSERT_EQ(tree.nq(), tree.nv());  // 1-DOF joints only: q and qd share the layout
  for (const json& sample : fixture.data["samples"]) {
    // Permute the reference's DOF order (URDF document order) into ours (depth first).
    Eigen::VectorXd q(tree.nq()), qd(tree.nv()), tau(tree.nv()), qddRef(tree.nv()), hRef(tree.nv());
    Eigen::MatrixXd mRef(tree.nv(), tree.nv());
    for (size_t i = 0; i < fixture.dofToV.size(); ++i) {
      const int v = fixture.dofToV[i];
      q(v) = sample["q"][i];
      qd(v) = sample["qdot"][i];
      tau(v) = sample["tau"][i];
      qddRef(v) = sample["qddot"][i];
      hRef(v) = sample["bias_forces"][i];
      for (size_t k = 0; k < fixture.dofToV.size(); ++k)
        mRef(v, fixture.dofToV[k]) = sample["mass_matrix"][i][k];
    }
    const Eigen::VectorXd qdd = forwardDynamics(tree, q, qd, tau);
    EXPECT_LE((qdd - qddRef).lpNorm<Eigen::Infinity>(), 1e-9 * qddRef.lpNorm<Eigen::Infinity>())
        << model << ": ours " << qdd.transpose() << "\nDART " << qddRef.transpose();
    EXPECT_LE((massMatrix(tree, q) - mRef).lpNorm<Eigen::Infinity>(),
              1e-10 * mRef.lpNorm<Eigen::Infinity>())
        << model;
    const double hScale =
        std::max({1.0, hRef.lpNorm<Eigen::Infinity>(), tau.lpNorm<Eigen::Infinity>()});
    EXPECT_LE((biasForces(tree, q, qd) - hRef).lpNorm<Eigen::Infinity>(), 1e-10 * hScale) << model;
  }
}
}  // namespace

TEST(ReferenceDynamics, Pendulum) {
  expectMatchesReference("pendulum");
}
TEST(ReferenceDynamics, DoublePendulum) {
  expectMatchesReference("double_pendulum");
}
TEST(ReferenceDynamics, Cartpole) {
  expectMatchesReference("cartpole");
}
TEST(ReferenceDynamics, KukaIiwa) {
  expectMatchesReference("kuka_iiwa");
}
TEST(ReferenceDynamics, Bravo7) {
  expectMatchesReference("bravo7");
}
TEST(ReferenceDynamics, R2d2) {
  expectMatchesReference("r2d2");
}
TEST(ReferenceDynamics, Solo12) {
  expectMatchesReference("solo12");
}
