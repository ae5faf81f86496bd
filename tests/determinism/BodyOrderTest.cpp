// What the order in which bodies are added changes (docs/reliability.md, "Determinism"):
//  - nothing, bit for bit, for a body that never shares an island with another dynamic body (free
//    flight, or contacts with static bodies only): each such body's step reads only its own state;
//  - the last bits, for bodies coupled in one island: the rows of an island's problem follow the
//    body slots and collider ids (creation order), so a permuted creation order sums in another
//    order and gives another, equally valid, trajectory. The documentation promises bit-identity
//    only for the same sequence of calls (SceneHashTest, PyramidDeterminismTest).
#include <gtest/gtest.h>
#include <coulomb/engine/World.hpp>

#include "scenes/SceneRegistry.hpp"

#include <algorithm>
#include <cstring>
#include <string>

using namespace coulomb;

namespace {

/// The scene with its dynamic bodies in reverse order (static and kinematic ones stay first).
engine::io::Scene reversedDynamics(engine::io::Scene scene) {
  const auto firstDynamic = std::stable_partition(
      scene.bodies.begin(), scene.bodies.end(),
      [](const auto& b) { return b.motionType != geometry::MotionType::Dynamic; });
  std::reverse(firstDynamic, scene.bodies.end());
  return scene;
}

bool sameBits(const engine::World& a, geometry::BodyId ia, const engine::World& b,
              geometry::BodyId ib) {
  const auto same = [](const auto& x, const auto& y, std::size_t n) {
    return std::memcmp(x.data(), y.data(), n * sizeof(double)) == 0;
  };
  return same(a.pose(ia).position, b.pose(ib).position, 3) &&
         same(a.pose(ia).rotation.coeffs(), b.pose(ib).rotation.coeffs(), 4) &&
         same(a.linearVelocity(ia), b.linearVelocity(ib), 3) &&
         same(a.angularVelocity(ia), b.angularVelocity(ib), 3);
}

/// Runs the scene and its reversed twin `steps` steps; the largest position difference of a body
/// (matched by name) and whether every body agrees bit for bit.
std::pair<double, bool> compareOrders(const engine::io::Scene& scene, int steps) {
  engine::World forward = engine::io::buildWorld(scene);
  engine::World backward = engine::io::buildWorld(reversedDynamics(scene));
  for (int n = 0; n < steps; ++n) {
    forward.step();
    backward.step();
  }
  double largest = 0.0;
  bool identical = true;
  for (const engine::BodyDesc& body : scene.bodies) {
    const geometry::BodyId a = forward.findBody(body.name), b = backward.findBody(body.name);
    largest = std::max(largest, (forward.pose(a).position - backward.pose(b).position).norm());
    identical = identical && sameBits(forward, a, backward, b);
  }
  return {largest, identical};
}

}  // namespace

TEST(BodyOrder, FreeBodiesAreBitIdenticalWhateverTheOrder) {
  for (const char* name : {"dzhanibekov", "projectile", "symmetric_top"}) {
    const engine::io::Scene scene = scenes::loadBuiltinScene(name);
    EXPECT_TRUE(compareOrders(scene, 500).second) << name;
  }
}

TEST(BodyOrder, BodiesAloneOnStaticGroundAreBitIdenticalWhateverTheOrder) {
  // Five boxes resting or sliding on the ground, far apart: five islands of one body each.
  engine::io::Scene scene = scenes::loadBuiltinScene("box_on_plane");
  const engine::BodyDesc boxDesc = scene.bodies.back();
  scene.bodies.pop_back();
  for (int k = 0; k < 5; ++k) {
    engine::BodyDesc b = boxDesc;
    b.name = "box" + std::to_string(k);
    b.pose.position.x() += 3.0 * k;
    b.linearVelocity = Eigen::Vector3d(0.5 * k, 0.0, 0.0);
    scene.bodies.push_back(b);
  }
  const auto [largest, identical] = compareOrders(scene, 200);
  EXPECT_TRUE(identical) << "largest difference " << largest << " m";
}

TEST(BodyOrder, CoupledBodiesAgreeToRoundingButNotBitForBit) {
  // A resting stack: one island, so the creation order is the order of its problem's rows.
  const engine::io::Scene scene = scenes::loadBuiltinScene("box_stack_10");
  const auto [largest, identical] = compareOrders(scene, 100);
  // Both orders keep the stack standing at the same place (measured difference: see
  // docs/reliability.md); whether the bits agree is not promised, so it is not asserted.
  EXPECT_LT(largest, 1e-4);
  RecordProperty("largest_difference_m", std::to_string(largest));
  RecordProperty("bit_identical", identical ? "yes" : "no");
  std::printf("box_stack_10 reversed: largest position difference %.3g m, bit-identical: %s\n",
              largest, identical ? "yes" : "no");
}
