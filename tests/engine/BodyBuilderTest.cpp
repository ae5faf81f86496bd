// Every validation error of body creation, triggered and checked for the value it names; a failed
// creation adds nothing to the World.
#include <gtest/gtest.h>
#include <coulomb/engine/BodyBuilder.hpp>
#include <coulomb/engine/CoulombError.hpp>
#include <coulomb/engine/World.hpp>
#include <coulomb/meshes/MakeConvexHull.hpp>

#include <cmath>
#include <functional>

using namespace coulomb;
using engine::BodyDesc;
using geometry::MotionType;

namespace {

BodyDesc validBox() {
  BodyDesc desc;
  desc.name = "crate";
  desc.shapes.push_back({geometry::Box{}, {}, {}, {}});
  return desc;
}

// Creating `desc` must fail with a message containing every fragment, and leave the World as is.
void expectRejected(const BodyDesc& desc, std::initializer_list<const char*> fragments) {
  engine::World world;
  world.createBody(validBox());
  const auto hashBefore = world.stateHash();
  try {
    world.createBody(desc);
    ADD_FAILURE() << "accepted an invalid body";
  } catch (const engine::CoulombError& e) {
    const std::string message = e.what();
    for (const char* fragment : fragments)
      EXPECT_NE(message.find(fragment), std::string::npos)
          << "'" << fragment << "' not in: " << message;
  }
  EXPECT_EQ(world.bodyCount(), 1u);
  EXPECT_EQ(world.colliders().size(), 1u);
  EXPECT_EQ(world.stateHash(), hashBefore);
}

BodyDesc modified(const std::function<void(BodyDesc&)>& change) {
  BodyDesc desc = validBox();
  change(desc);
  return desc;
}

geometry::SpatialInertia explicitMass(double mass, const Eigen::Vector3d& moments) {
  return {mass, Eigen::Vector3d::Zero(), moments.asDiagonal()};
}

}  // namespace

TEST(BodyBuilder, ValidBodyResolves) {
  const engine::ResolvedBody body = engine::resolveBody(validBox(), {});
  EXPECT_NEAR(body.massProperties.mass, 1000.0, 1e-9);
  ASSERT_EQ(body.shapes.size(), 1u);
}

TEST(BodyBuilder, NonFinitePose) {
  expectRejected(modified([](BodyDesc& d) { d.pose.position.y() = NAN; }),
                 {"crate", "position[1]", "not finite"});
  expectRejected(modified([](BodyDesc& d) { d.pose.rotation.coeffs()[0] = INFINITY; }),
                 {"orientation", "not finite"});
  expectRejected(modified([](BodyDesc& d) { d.pose.rotation.coeffs() *= 2.0; }),
                 {"unit quaternion", "norm 2"});
}

TEST(BodyBuilder, NonFiniteVelocity) {
  expectRejected(modified([](BodyDesc& d) { d.angularVelocity.z() = NAN; }),
                 {"angular_velocity[2]"});
  expectRejected(modified([](BodyDesc& d) { d.linearVelocity.x() = -INFINITY; }),
                 {"linear_velocity[0]"});
}

TEST(BodyBuilder, ZeroOrNegativeMassAndDensity) {
  expectRejected(modified([](BodyDesc& d) {
                   d.mass = explicitMass(0.0, {1, 1, 1});
                 }),
                 {"mass must be finite and > 0", "got 0"});
  expectRejected(modified([](BodyDesc& d) { d.mass = explicitMass(-3.0, {1, 1, 1}); }), {"got -3"});
  expectRejected(modified([](BodyDesc& d) { d.density = -1.0; }), {"density"});
}

TEST(BodyBuilder, InertiaBreakingTheTriangleInequality) {
  expectRejected(modified([](BodyDesc& d) {
                   d.mass = explicitMass(1.0, {1, 1, 5});
                 }),
                 {"triangle inequality", "5"});
  expectRejected(modified([](BodyDesc& d) {
                   d.mass = explicitMass(1.0, {1, 0, 1});
                 }),
                 {"positive definite"});
  expectRejected(modified([](BodyDesc& d) {
                   d.mass = explicitMass(1.0, {1, 1, 1});
                   d.mass->centerOfMass.x() = NAN;
                 }),
                 {"center_of_mass"});
}

TEST(BodyBuilder, DegenerateShapes) {
  expectRejected(
      modified([](BodyDesc& d) { d.shapes[0].shape = geometry::Box{Eigen::Vector3d(1, 0, 1)}; }),
      {"shapes[0]", "box", "half_extents[1]"});
  expectRejected(modified([](BodyDesc& d) {
                   geometry::ConvexHull flat;
                   flat.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}};
                   d.shapes.push_back({flat, {}, {}, {}});
                 }),
                 {"shapes[1]", "coplanar"});
  expectRejected(modified([](BodyDesc& d) { d.shapes[0].localPose.position.z() = NAN; }),
                 {"shapes[0].position[2]"});
}

TEST(BodyBuilder, MaterialsAndPlanes) {
  expectRejected(modified([](BodyDesc& d) { d.shapes[0].material.friction = -0.1; }),
                 {"shapes[0].material.friction"});
  expectRejected(modified([](BodyDesc& d) { d.shapes[0].material.restitution = 1.5; }),
                 {"restitution"});
  expectRejected(modified([](BodyDesc& d) { d.shapes[0].shape = geometry::Plane{}; }),
                 {"plane", "only a static body", "dynamic"});
}

TEST(BodyBuilder, DynamicBodyNeedsMass) {
  expectRejected(modified([](BodyDesc& d) { d.shapes.clear(); }),
                 {"needs finite shapes or an explicit mass"});
  BodyDesc marker = validBox();
  marker.shapes.clear();
  marker.motionType = MotionType::Static;
  EXPECT_NO_THROW(engine::resolveBody(marker, {}));
}

// The core takes hulls with faces only (qhull is the meshes component): points alone are refused
// with the way to build them, and makeConvexHull's hull is used as it is.
TEST(BodyBuilder, ConvexHullsNeedTheirFaces) {
  BodyDesc desc = validBox();
  geometry::ConvexHull hull;
  for (int i = 0; i < 8; ++i)
    hull.vertices.emplace_back((i & 1) ? 0.5 : -0.5, (i & 2) ? 0.5 : -0.5, (i & 4) ? 0.5 : -0.5);
  desc.shapes[0].shape = hull;
  expectRejected(desc, {"shapes[0]", "points only", "coulomb::makeConvexHull"});
  desc.shapes[0].shape = geometry::makeConvexHull(hull.vertices);
  const engine::ResolvedBody body = engine::resolveBody(desc, {});
  EXPECT_EQ(std::get<geometry::ConvexHull>(*body.shapes[0].shape).triangles.size(), 12u);
  EXPECT_NEAR(body.massProperties.mass, 1000.0, 1e-9);
}
