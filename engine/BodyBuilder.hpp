#pragma once
// Turns a BodyDesc into what the World stores, validating every value on the way (golden rule 8:
// validate at the boundary). Nothing here touches a World, so a failure leaves it unchanged.
#include <coulomb/engine/BodyDesc.hpp>
#include <coulomb/engine/WorldSettings.hpp>

#include <memory>
#include <vector>

namespace coulomb::engine {

struct ResolvedShape {
  std::shared_ptr<const geometry::Shape> shape;  // convex hulls have their faces built
  geometry::Pose localPose;                      // in the COM (body) frame
  geometry::Material material;
  geometry::CollisionFilter filter;
  bool sensor = false;
  std::uint64_t userData = 0;
};

struct ResolvedBody {
  geometry::Pose comPose;                   // body (COM) frame in world
  geometry::SpatialInertia massProperties;  // COM in the reference frame; zero mass if not dynamic
  std::vector<ResolvedShape> shapes;
};

/// Throws CoulombError naming the body and the wrong value: non-finite or non-unit pose,
/// non-finite velocity, degenerate shape (shapes[k]), bad material, a plane on a moving body,
/// zero/negative mass or density, an inertia that is not positive definite or breaks the triangle
/// inequality, a dynamic body with neither finite shapes nor an explicit mass.
ResolvedBody resolveBody(const BodyDesc& desc, const WorldSettings& settings);

/// Why a convex hull given as points alone is refused: the core builds no hulls (qhull is the
/// optional component coulomb::meshes; scene files build theirs when they are read).
inline constexpr const char* kHullNeedsFaces =
    "convex_hull given as points only: build its faces with coulomb::makeConvexHull(points) "
    "(component coulomb::meshes, <coulomb/meshes.hpp>)";

}  // namespace coulomb::engine
