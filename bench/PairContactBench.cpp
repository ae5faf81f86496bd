// Narrow-phase cost of the pairs that get their manifold from supporting features
// (geometry/FeatureContacts, docs/collision.md "Per-pair behaviour"), against FCL's collide alone
// for the same pose, which is what these pairs cost when they got FCL's one point.
// Each pair rests 1 mm deep; args: 0 cylinder on box, 1 can on can, 2 capsule on hull,
// 3 cylinder on hull, 4 hull on a 200-triangle mesh, 5 box on a 200-triangle mesh, 6 a
// 12-triangle mesh block on the 200-triangle mesh (mesh-mesh: FCL's own contacts are unusable).
// Counter: points of the raw manifold (before the reduction to 4).
#include <coulomb/geometry/NarrowPhase.hpp>

#include <benchmark/benchmark.h>

#include <Eigen/Geometry>

#include <memory>
#include <numbers>

#include "bench/ShapeFixtures.hpp"

namespace {

using namespace coulomb::geometry;
using coulomb::samples::boxHull;
using coulomb::samples::gridSlab;

struct PairSetup {
  FclScene scene{0.01};
  Collider a, b;
  Pose pa, pb;

  explicit PairSetup(int which) {
    const double depth = 1e-3;
    Shape lower, upper;
    pa = Pose::identity();
    switch (which) {
      case 0:
        lower = Box{{1.0, 1.0, 0.1}}, upper = Cylinder{0.2, 0.3};
        pb = Pose::translation({0.05, 0.0, 0.4 - depth});
        break;
      case 1:
        lower = Cylinder{0.1, 0.2}, upper = Cylinder{0.1, 0.2};
        pb = Pose::translation({0.0, 0.0, 0.4 - depth});
        break;
      case 2:
        lower = boxHull({1.0, 1.0, 0.5}), upper = Capsule{0.05, 0.3};
        pb = {Eigen::Quaterniond(Eigen::AngleAxisd(std::numbers::pi / 2, Eigen::Vector3d::UnitY())),
              {0.0, 0.0, 0.55 - depth}};
        break;
      case 3:
        lower = boxHull({1.0, 1.0, 0.5}), upper = Cylinder{0.2, 0.3};
        pb = Pose::translation({0.0, 0.1, 0.8 - depth});
        break;
      case 4:
        lower = gridSlab(10, 1.0), upper = boxHull({0.2, 0.15, 0.1});
        pb = Pose::translation({0.13, 0.07, 0.1 - depth});
        break;
      case 5:
        lower = gridSlab(10, 1.0), upper = Box{{0.2, 0.15, 0.1}};
        pb = Pose::translation({0.13, 0.07, 0.1 - depth});
        break;
      default:
        lower = gridSlab(10, 1.0), upper = gridSlab(1, 0.2);
        pb = Pose::translation({0.13, 0.07, 0.2 - depth});
        break;
    }
    a.id = {0, 0};
    a.body = {0, 0};
    a.shape = std::make_shared<const Shape>(lower);
    b.id = {1, 0};
    b.body = {1, 0};
    b.shape = std::make_shared<const Shape>(upper);
    scene.upsert(a.id, a.shape);
    scene.upsert(b.id, b.shape);
    scene.setPose(a.id, pa);
    scene.setPose(b.id, pb);
    scene.updateTree();
  }
};

void BM_PairManifold(benchmark::State& state) {
  PairSetup setup(static_cast<int>(state.range(0)));
  NarrowPhase narrow;
  PairContact out;
  std::string error;
  for (auto _ : state) {
    narrow.contactPair(setup.a, setup.pa, setup.b, setup.pb, setup.scene, out, error);
    benchmark::DoNotOptimize(out.points.data());
  }
  state.counters["points"] = static_cast<double>(out.points.size());
}

void BM_FclCollideOnly(benchmark::State& state) {
  PairSetup setup(static_cast<int>(state.range(0)));
  const bool mesh = state.range(0) >= 4;
  std::size_t points = 0;
  for (auto _ : state) {
    const FclCollideResult hit = setup.scene.collide(setup.a.id, setup.b.id, mesh ? 64 : 4);
    points = hit.contacts.size();
    benchmark::DoNotOptimize(hit.contacts.data());
  }
  state.counters["points"] = static_cast<double>(points);
}

}  // namespace

BENCHMARK(BM_PairManifold)->DenseRange(0, 6)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_FclCollideOnly)->DenseRange(0, 6)->Unit(benchmark::kMicrosecond);

BENCHMARK_MAIN();
