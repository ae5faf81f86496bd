#pragma once
// Scene queries on a World between steps (docs/embedding.md, "Scene queries"), component
// coulomb::core: ray casts, shape casts, overlaps, AABB queries and closest points.
#include <coulomb/engine/WorldQueries.hpp>
#include <coulomb/world.hpp>

namespace coulomb {

using engine::WorldQueries;
using geometry::Aabb;
using geometry::ClosestPoints;
using geometry::QueryFilter;
using geometry::RayHit;
using geometry::ShapeHit;

}  // namespace coulomb
