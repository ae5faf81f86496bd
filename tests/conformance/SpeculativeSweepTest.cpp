// Velocity-swept speculative margins (geometry/SweptMargin.hpp, docs/collision.md) and the
// restitution law of speculative points (engine/ContactRowsEmitter.cpp), the fix of the box pile
// sinking into its floor (docs/scene-specifications.md B1, docs/conformance.md):
// - tilted boxes arriving at ~3 cm per step (6x the fixed 5 mm margin) onto the floor and onto
//   each other: no corner below -5 mm (the pile's criterion), no overlap deeper than 5 mm, no box
//   through another. With the fixed margin alone (speculativeSweep = 0) the same drop fails,
//   which the test also checks, so it can fail;
// - two columns of the pile itself (10 boxes each, landing on each other at 2-5 m/s): no corner
//   below -5 mm, no box-box overlap deeper than 5 mm (the edge-edge manifolds of nearly parallel
//   faces let them sink 14 cm: geometry/BoxContacts.cpp, kEdgeRelativeTolerance);
// - a ball reaching the floor from a speculative gap bounces by Newton's law at the moment the
//   gap closes (u_N+ = e |u_N-|), not a step later from what is left of its speed;
// - a speculative row that does not close within the step applies no impulse at all.
#include <gtest/gtest.h>

#include <coulomb/engine/World.hpp>

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <vector>

using namespace coulomb;

namespace {

constexpr double kH = 0.01;  // [s] docs/scene-specifications.md dt
constexpr double kHalf =
    0.1;  // [m] half side of the 0.2 m cubes (docs/scene-specifications.md box(0.1, m))
constexpr double kCornerFloor = -0.005;  // [m] the pile's criterion (docs/conformance.md)
constexpr double kMaxOverlap = 0.005;    // [m] deepest manifold point allowed

engine::World makeWorld(double sweep, double friction = 0.6, double restitution = 0.0) {
  engine::WorldSettings settings;
  settings.collision.speculativeSweep = sweep;
  engine::World world(settings);
  engine::BodyDesc floor;
  floor.motionType = geometry::MotionType::Static;
  floor.shapes.push_back({geometry::Plane{}, {}, {friction, restitution}, {}});
  world.createBody(floor);
  return world;
}

geometry::BodyId addBox(engine::World& world, const Eigen::Vector3d& position,
                        const Eigen::Quaterniond& rotation, double speed) {
  engine::BodyDesc box;
  box.pose.position = position;
  box.pose.rotation = rotation;
  box.linearVelocity = {0.0, 0.0, -speed};
  box.mass = geometry::SpatialInertia{1.0, Eigen::Vector3d::Zero(),
                                      Eigen::Matrix3d::Identity() * (8.0 * kHalf * kHalf / 12.0)};
  box.shapes.push_back({geometry::Box{Eigen::Vector3d::Constant(kHalf)}, {}, {0.6, 0.0}, {}});
  return world.createBody(box);
}

double lowestCorner(const engine::World& world, geometry::BodyId id) {
  const geometry::Pose& pose = world.pose(id);
  double lowest = std::numeric_limits<double>::infinity();
  for (int k = 0; k < 8; ++k) {
    const Eigen::Vector3d corner(k & 1 ? kHalf : -kHalf, k & 2 ? kHalf : -kHalf,
                                 k & 4 ? kHalf : -kHalf);
    lowest = std::min(lowest, pose.apply(corner).z());
  }
  return lowest;
}

struct DropResult {
  double lowestCorner = std::numeric_limits<double>::infinity();  // [m] over the run
  double deepestOverlap = 0.0;                                    // [m] over the run
  bool stackedInOrder = true;  // every upper box still above its lower box at the end
};

// Five boxes tilted by different angles fall onto the floor, and a column of three falls onto a
// resting box, every one arriving at 2.5-3.5 m/s (2.5-3.5 cm per step). Their heights put the
// lowest corner 0-2.8 cm above the contact in the step before it, so that with a 5 mm margin most
// of them are found only once they overlap.
DropResult dropBoxes(double sweep) {
  engine::World world = makeWorld(sweep);
  std::vector<geometry::BodyId> floorBoxes;
  for (int k = 0; k < 5; ++k) {
    const Eigen::Quaterniond tilt(Eigen::AngleAxisd(0.1 + 0.07 * k, Eigen::Vector3d::UnitX()) *
                                  Eigen::AngleAxisd(0.05 * k, Eigen::Vector3d::UnitY()));
    floorBoxes.push_back(addBox(world, {0.6 * k, 0.0, 0.25 + 0.0057 * k}, tilt, 2.5 + 0.25 * k));
  }
  // A box at rest on the floor and a column of three falling onto it.
  std::array<geometry::BodyId, 4> column{};
  column[0] = addBox(world, {0.0, 1.0, kHalf}, Eigen::Quaterniond::Identity(), 0.0);
  for (int k = 1; k < 4; ++k) {
    const Eigen::Quaterniond tilt(Eigen::AngleAxisd(
        0.03 + 0.03 * k, k % 2 ? Eigen::Vector3d::UnitY() : Eigen::Vector3d::UnitX()));
    column[k] = addBox(world, {0.0, 1.0, 0.35 + 0.33 * k + 0.0043 * k}, tilt, 3.0 + 0.2 * k);
  }
  DropResult result;
  for (int step = 0; step < 150; ++step) {
    world.step(kH);
    for (std::size_t i = 0; i < world.state().size(); ++i) {
      const geometry::BodyId id = world.idAt(i);
      if (id.valid() && world.state().isDynamic(i))
        result.lowestCorner = std::min(result.lowestCorner, lowestCorner(world, id));
    }
    for (const geometry::ContactManifold& m : world.contacts())
      for (const geometry::ContactPoint& p : m.activePoints())
        result.deepestOverlap = std::max(result.deepestOverlap, p.depth);
  }
  for (int k = 1; k < 4; ++k)  // resting cubes: centres about 0.2 m apart, in order
    result.stackedInOrder =
        result.stackedInOrder &&
        world.pose(column[k]).position.z() > world.pose(column[k - 1]).position.z() + 0.15;
  std::printf("sweep %.1f: lowest corner %.4g m, deepest overlap %.4g m, in order %d\n", sweep,
              result.lowestCorner, result.deepestOverlap, result.stackedInOrder);
  return result;
}

// Two columns of the 1000-box pile (docs/scene-specifications.md B1: boxes i = ix + 10 iy + 100 iz
// of columns (ix, iy) = (6, 4) and (7, 4), iz = 0..9, yawed by the golden angle and tilted by up to
// 0.1 rad) fall onto the floor, each box landing on the one below at 2-5 m/s. Boxes stacked face on
// face with a small relative tilt and yaw have edge-cross axes a few degrees off the face normal
// that separate them by 1e-4 to 1e-3 m more than the face axis: box-box contacts that took such an
// axis got one edge point, and the upper box pivoted about it and sank into the lower one (box 146
// 1.7 cm into box 46 at step 20, box 247 into box 147 by 2.8 cm at step 27 and 10 cm by step 40).
DropResult dropPileColumns(int steps) {
  engine::World world = makeWorld(1.0);
  std::vector<geometry::BodyId> boxes;
  for (int iz = 0; iz < 10; ++iz)
    for (int ix : {6, 7}) {
      const int i = ix + 10 * 4 + 100 * iz;
      const double yaw = std::fmod(2.399963229728653 * i, 2.0 * std::numbers::pi);
      const double tilt = 0.1 * std::sin(1.7 * i);
      const Eigen::Quaterniond rotation(Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) *
                                        Eigen::AngleAxisd(tilt, Eigen::Vector3d::UnitX()));
      boxes.push_back(
          addBox(world, {(ix - 4.5) * 0.35, (4 - 4.5) * 0.35, 0.15 + 0.35 * iz}, rotation, 0.0));
    }
  DropResult result;
  for (int step = 0; step < steps; ++step) {
    world.step(kH);
    for (const geometry::BodyId id : boxes)
      result.lowestCorner = std::min(result.lowestCorner, lowestCorner(world, id));
    for (const geometry::ContactManifold& m : world.contacts())
      for (const geometry::ContactPoint& p : m.activePoints())
        result.deepestOverlap = std::max(result.deepestOverlap, p.depth);
  }
  for (std::size_t k = 2; k < boxes.size(); ++k)  // each box still above the one it fell on
    result.stackedInOrder =
        result.stackedInOrder &&
        world.pose(boxes[k]).position.z() > world.pose(boxes[k - 2]).position.z() + 0.15;
  std::printf("pile columns, %d steps: lowest corner %.4g m, deepest overlap %.4g m, in order %d\n",
              steps, result.lowestCorner, result.deepestOverlap, result.stackedInOrder);
  return result;
}

}  // namespace

TEST(SpeculativeSweep, PileColumnsLandFaceOnFaceWithoutSinking) {
  const DropResult columns = dropPileColumns(70);  // the top boxes land at step ~55
  EXPECT_GT(columns.lowestCorner, kCornerFloor);
  EXPECT_LT(columns.deepestOverlap, kMaxOverlap);
}

TEST(SpeculativeSweep, FastTiltedBoxesNeitherSinkNorPassThrough) {
  const DropResult swept = dropBoxes(1.0);  // the default
  EXPECT_GT(swept.lowestCorner, kCornerFloor);
  EXPECT_LT(swept.deepestOverlap, kMaxOverlap);
  EXPECT_TRUE(swept.stackedInOrder);
}

TEST(SpeculativeSweep, TheFixedMarginAloneFailsTheSameDrop) {
  const DropResult fixed = dropBoxes(0.0);  // the behaviour before: 5 mm whatever the speed
  EXPECT_TRUE(fixed.lowestCorner < kCornerFloor || fixed.deepestOverlap > kMaxOverlap);
}

// A ball (r 0.1, e 0.5, frictionless) dropped from 0.5 m: every impact is found as a speculative
// point one step ahead. Newton's law at the moment it closes gives a rebound of e times the
// approach speed of that step, which the discrete fall puts within 2 g h of sqrt(2 g H).
TEST(SpeculativeSweep, ClosingSpeculativePointBouncesByNewtonsLaw) {
  constexpr double kRadius = 0.1, kDrop = 0.5, kE = 0.5, kG = 9.81;
  engine::World world = makeWorld(1.0, 0.0, kE);
  engine::BodyDesc ball;
  ball.pose.position = {2.0, 0.0, kRadius + kDrop};
  ball.shapes.push_back({geometry::Sphere{kRadius}, {}, {0.0, kE}, {}});
  const geometry::BodyId id = world.createBody(ball);
  double fastestDown = 0.0, rebound = 0.0;
  for (int step = 0; step < 60 && rebound == 0.0; ++step) {
    const double before = world.linearVelocity(id).z();
    world.step(kH);
    const double after = world.linearVelocity(id).z();
    if (after > 0.0) {
      fastestDown = -(before - kG * kH);  // v* of the impact step
      rebound = after;
    }
    EXPECT_GT(world.pose(id).position.z() - kRadius, -1e-9) << "step " << step;
  }
  const double analytic = std::sqrt(2.0 * kG * kDrop);
  std::printf("approach %.6f m/s, rebound %.6f m/s, e sqrt(2 g H) = %.6f m/s\n", fastestDown,
              rebound, kE * analytic);
  EXPECT_NEAR(rebound, kE * fastestDown, 1e-6);  // Newton's law, to the solver's tolerance
  EXPECT_NEAR(rebound, kE * analytic, kE * 2.0 * kG * kH);
}

// Without gravity, a ball skims 1 cm above the floor at 5 m/s and sinks at 0.2 m/s: its swept
// margin (5 cm) makes a speculative point, which would close only after 5 steps, so the row
// must apply nothing, friction included: the velocity stays exactly what it was.
TEST(SpeculativeSweep, NonClosingSpeculativeRowAppliesNoImpulse) {
  engine::World world = makeWorld(1.0);
  world.setGravity(Eigen::Vector3d::Zero());
  engine::BodyDesc ball;
  ball.pose.position = {0.0, 0.0, 0.11};
  ball.linearVelocity = {5.0, 0.0, -0.2};
  ball.shapes.push_back({geometry::Sphere{0.1}, {}, {0.6, 0.0}, {}});
  const geometry::BodyId id = world.createBody(ball);
  world.step(kH);
  ASSERT_EQ(world.contacts().size(), 1u);
  const geometry::ContactPoint& point = world.contacts()[0].points[0];
  EXPECT_NEAR(point.depth, -0.01, 1e-12);
  EXPECT_EQ(point.normalImpulse, 0.0);
  EXPECT_EQ(world.linearVelocity(id), Eigen::Vector3d(5.0, 0.0, -0.2));
  EXPECT_EQ(world.angularVelocity(id), Eigen::Vector3d::Zero());
}
