// Articulation speed: ABA time per step (and per link) on serial chains and URDF robots, CRBA +
// Cholesky for contrast, and the contact-response (Delassus) assembly of a tree with 10 contact
// points. Each benchmark also reports a residual: |M qdd + h - tau| for ABA, the symmetry of W.
#include <benchmark/benchmark.h>
#include <coulomb/integrators/ArticulationIntegrator.hpp>
#include <coulomb/joints/tree/ArticulationImpulse.hpp>
#include <coulomb/joints/tree/TreeDynamics.hpp>

#include <nlohmann/json.hpp>

#include <bench/AbaChain.hpp>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <cmath>
#include <fstream>
#include <string>

using namespace coulomb::joints::tree;
using coulomb::geometry::Pose;
using coulomb::geometry::SpatialInertia;
using coulomb::samples::serialChain;
using coulomb::samples::wave;

namespace {
Eigen::Vector3d vector3(const nlohmann::json& j) {
  return {j[0].get<double>(), j[1].get<double>(), j[2].get<double>()};
}

/// The fixture format of tests/data/urdf/ORIGIN.md.
Articulation urdfModel(const std::string& model) {
  std::ifstream in(std::string(COULOMB_TEST_DATA_DIR) + "/urdf/" + model + "/tree.json");
  const nlohmann::json data = nlohmann::json::parse(in);
  std::vector<TreeLink> links;
  for (const auto& l : data["links"]) {
    const auto& j = l["joint"];
    const auto& w = j["quaternion_wxyz"];
    const Pose origin{Eigen::Quaterniond(w[0], w[1], w[2], w[3]).normalized(), vector3(j["xyz"])};
    const std::string type = j["type"], name = j["name"];
    TreeJoint joint = type == "fixed"       ? TreeJoint::fixed(name, origin)
                      : type == "prismatic" ? TreeJoint::prismatic(name, origin, vector3(j["axis"]))
                                            : TreeJoint::revolute(name, origin, vector3(j["axis"]));
    SpatialInertia inertia{l["mass"], vector3(l["com"]), Eigen::Matrix3d::Zero()};
    const auto& i = l["inertia_about_com"];
    inertia.inertiaAboutCom << i[0], i[3], i[4], i[3], i[1], i[5], i[4], i[5], i[2];
    links.push_back({l["name"], l["parent"], joint, inertia});
  }
  return Articulation(links);
}

void runAba(benchmark::State& state, const Articulation& tree) {
  const Eigen::VectorXd q = wave(tree.nq(), 0.1), qd = wave(tree.nv(), 0.2),
                        tau = wave(tree.nv(), 0.3);
  Eigen::VectorXd qdd;
  for (auto _ : state) {
    qdd = forwardDynamics(tree, q, qd, tau);
    benchmark::DoNotOptimize(qdd.data());
  }
  state.counters["links"] = tree.linkCount();
  state.counters["dofs"] = tree.nv();
  state.counters["time_per_link"] =
      benchmark::Counter(tree.linkCount(), benchmark::Counter::kIsIterationInvariantRate |
                                               benchmark::Counter::kInvert);
  state.counters["residual"] = coulomb::samples::abaResidual(tree);
}

void BM_AbaSerialChain(benchmark::State& state) {
  runAba(state, serialChain(static_cast<int>(state.range(0))));
}
BENCHMARK(BM_AbaSerialChain)->Arg(10)->Arg(100)->Arg(1000)->Unit(benchmark::kMicrosecond);

void BM_AbaUrdf(benchmark::State& state, const char* model) {
  runAba(state, urdfModel(model));
}
BENCHMARK_CAPTURE(BM_AbaUrdf, kuka_iiwa, "kuka_iiwa")->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_AbaUrdf, bravo7, "bravo7")->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_AbaUrdf, r2d2, "r2d2")->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_AbaUrdf, solo12, "solo12")->Unit(benchmark::kMicrosecond);

/// For contrast: qdd by CRBA (O(n^2) to build M) plus a dense Cholesky solve (O(n^3)).
void BM_CrbaCholeskySerialChain(benchmark::State& state) {
  const Articulation tree = serialChain(static_cast<int>(state.range(0)));
  const Eigen::VectorXd q = wave(tree.nq(), 0.1), qd = wave(tree.nv(), 0.2),
                        tau = wave(tree.nv(), 0.3);
  Eigen::VectorXd qdd;
  for (auto _ : state) {
    qdd = massMatrix(tree, q).llt().solve(tau - biasForces(tree, q, qd));
    benchmark::DoNotOptimize(qdd.data());
  }
  state.counters["residual"] = (qdd - forwardDynamics(tree, q, qd, tau)).lpNorm<Eigen::Infinity>();
}
BENCHMARK(BM_CrbaCholeskySerialChain)->Arg(10)->Arg(100)->Arg(1000)->Unit(benchmark::kMicrosecond);

/// One semi-implicit Euler step (ABA + manifold update) of a floating-base chain.
void BM_StepFloatingChain(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  std::vector<TreeLink> links = serialChain(n).links();
  links[0].joint = TreeJoint::floating("base");
  const Articulation tree(links);
  Eigen::VectorXd q = tree.neutralConfiguration(), qd = wave(tree.nv(), 0.2);
  const Eigen::VectorXd tau = Eigen::VectorXd::Zero(tree.nv());
  for (auto _ : state) {
    coulomb::integrators::stepArticulation(tree, q, qd, tau, 1e-4);
    benchmark::DoNotOptimize(q.data());
  }
  state.counters["time_per_link"] = benchmark::Counter(
      n, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}
BENCHMARK(BM_StepFloatingChain)->Arg(10)->Arg(100)->Arg(1000)->Unit(benchmark::kMicrosecond);

/// Contact response of solo12 (the quadruped, 17 links) with 10 contact points (3 rows each):
/// articulated inertias at q, then the dense 30 x 30 W = J M^-1 J^T, or one matrix-free W x.
std::vector<PointImpulseRow> tenContacts(const Articulation& tree,
                                         const ArticulationImpulse& impulse) {
  std::vector<PointImpulseRow> rows;
  for (int c = 0; c < 10; ++c) {
    const int link = tree.linkCount() - 1 - (c * 3) % tree.linkCount();
    const Eigen::Vector3d point = impulse.kinematics().worldPoses[static_cast<size_t>(link)].apply(
        Eigen::Vector3d(0.01 * c, 0, -0.02));
    const Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
    rows.push_back({link, point, normal});
    rows.push_back({link, point, Eigen::Vector3d::UnitX()});
    rows.push_back({link, point, Eigen::Vector3d::UnitY()});
  }
  return rows;
}

void BM_DelassusDense10Contacts(benchmark::State& state) {
  const Articulation tree = urdfModel("solo12");
  const Eigen::VectorXd q = wave(tree.nq(), 0.1);
  Eigen::MatrixXd w;
  for (auto _ : state) {
    const ArticulationImpulse impulse(tree, q);
    w = impulse.delassus(tenContacts(tree, impulse));
    benchmark::DoNotOptimize(w.data());
  }
  state.counters["rows"] = static_cast<double>(w.rows());
  state.counters["min_eig"] = w.selfadjointView<Eigen::Lower>().eigenvalues().minCoeff();
}
BENCHMARK(BM_DelassusDense10Contacts)->Unit(benchmark::kMicrosecond);

void BM_DelassusMatrixFree10Contacts(benchmark::State& state) {
  const Articulation tree = urdfModel("solo12");
  const ArticulationImpulse impulse(tree, wave(tree.nq(), 0.1));
  const std::vector<PointImpulseRow> rows = tenContacts(tree, impulse);
  const Eigen::VectorXd x = wave(static_cast<int>(rows.size()), 0.4);
  Eigen::VectorXd wx;
  for (auto _ : state) {
    wx = impulse.applyDelassus(rows, x);
    benchmark::DoNotOptimize(wx.data());
  }
  state.counters["residual"] = (wx - impulse.delassus(rows) * x).lpNorm<Eigen::Infinity>();
}
BENCHMARK(BM_DelassusMatrixFree10Contacts)->Unit(benchmark::kMicrosecond);
}  // namespace

BENCHMARK_MAIN();
