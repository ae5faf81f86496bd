// Articulations in the engine: assembly of the contact problem for a tree with 10 contacts (the
// tree part of W by impulse-level ABA plus the free-body part), and ms per step of the
// arm_pushing_boxes scene. Each benchmark reports a check beside the time: W's symmetry, the
// number of unknowns, the arm island's size.
#include <benchmark/benchmark.h>
#include <coulomb/engine/World.hpp>
#include <coulomb/io/SceneLoader.hpp>
#include <coulomb/joints/ContactRows.hpp>

#include <string>

using namespace coulomb;
using geometry::Pose;
using joints::tree::TreeJoint;

namespace {

/// A fixed-base serial chain of `links` revolute links 0.2 m apart (boxes along x), lying over a
/// row of free boxes, and 10 contact row blocks: link k touches box k (k < 10), or the ground.
struct TreeWithContacts {
  engine::World world;
  geometry::ArticulationId tree;
  joints::RowSet rows;
};

TreeWithContacts makeTreeWithContacts(int links) {
  TreeWithContacts out;
  engine::ArticulationDesc desc;
  desc.name = "chain";
  for (int i = 0; i < links; ++i) {
    engine::ArticulationLinkDesc link;
    link.name = std::to_string(i);  // (GCC 12 -Wrestrict misfires on "l" + std::to_string)
    link.parent = i - 1;
    const Eigen::Vector3d axis = i % 2 == 0 ? Eigen::Vector3d::UnitY() : Eigen::Vector3d::UnitZ();
    link.joint = TreeJoint::revolute(
        std::to_string(i), Pose::translation({i == 0 ? 0.0 : 0.2, 0, i == 0 ? 0.3 : 0}), axis);
    link.inertia = geometry::SpatialInertia{1.0, {0.1, 0, 0}, Eigen::Matrix3d::Identity() * 0.004};
    desc.links.push_back(link);
  }
  out.tree = out.world.createArticulation(desc);
  for (int k = 0; k < 10; ++k) {
    const int linkIndex = k * links / 10;
    const geometry::BodyId proxy = out.world.articulations().linkBody(out.tree, linkIndex);
    engine::BodyDesc box;
    box.pose = Pose::translation({0.2 * linkIndex + 0.1, 0, 0.15});
    box.shapes.push_back({geometry::Box{Eigen::Vector3d::Constant(0.1)}, {}, {}, {}});
    const geometry::BodyId boxId = out.world.createBody(box);
    joints::ContactPointFrame frame;
    frame.bodyA = boxId;
    frame.bodyB = proxy;
    frame.point = {0.2 * linkIndex + 0.1, 0, 0.25};
    frame.centreA = out.world.pose(boxId).position;
    frame.centreB = out.world.pose(proxy).position;
    frame.friction = 0.5;
    out.rows.blocks.push_back(joints::makeContactRows(frame));
  }
  return out;
}

void BM_TreeContactAssembly(benchmark::State& state) {
  TreeWithContacts scene = makeTreeWithContacts(static_cast<int>(state.range(0)));
  const engine::ProblemAssembler assembler;
  double asymmetry = 0.0;
  for (auto _ : state) {
    engine::AssembledProblem problem =
        assembler.assemble(scene.rows, scene.world.state(), &scene.world.articulations());
    benchmark::DoNotOptimize(problem.problem.q.data());
    const Eigen::MatrixXd& W = *problem.problem.W.denseMatrix();
    asymmetry = (W - W.transpose()).cwiseAbs().maxCoeff();
  }
  state.counters["links"] = static_cast<double>(state.range(0));
  state.counters["unknowns"] = static_cast<double>(scene.rows.rowCount());
  state.counters["W_asymmetry"] = asymmetry;
}
BENCHMARK(BM_TreeContactAssembly)->Arg(10)->Arg(100)->Arg(1000)->Unit(benchmark::kMicrosecond);

void BM_ArmPushingBoxesStep(benchmark::State& state) {
  const engine::io::Scene scene = engine::io::loadSceneFile(
      std::string(COULOMB_SOURCE_DIR) + "/samples/scenes/arm_pushing_boxes.json");
  std::size_t largestIsland = 0;
  for (auto _ : state) {
    state.PauseTiming();
    engine::World world = engine::io::buildWorld(scene);
    state.ResumeTiming();
    for (std::uint64_t k = 0; k < scene.steps; ++k) {
      const engine::StepReport& report = world.step();
      for (const auto& island : report.islands)
        largestIsland = std::max(largestIsland, island.bodies);
    }
  }
  state.counters["steps"] = static_cast<double>(scene.steps);
  state.counters["time_per_step"] = benchmark::Counter(
      static_cast<double>(scene.steps),
      benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
  state.counters["largest_island"] = static_cast<double>(largestIsland);
}
BENCHMARK(BM_ArmPushingBoxesStep)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
