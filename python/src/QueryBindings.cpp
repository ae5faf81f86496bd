// The scene queries of coulomb.World (docs/python.md "Scene queries"; engine/WorldQueries.hpp):
// ray casts, shape casts, overlaps, AABB queries and closest points of two bodies, on the world
// as the last step left it. Shapes are given as in the JSON scene format ({"type": "sphere",
// "radius": 0.1}); hits name bodies and colliders by integer handles.
#include <coulomb/io/SceneLoader.hpp>

#include <pybind11/stl.h>

#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "Bindings.hpp"
#include "NumpyConversion.hpp"
#include "PyWorld.hpp"
#include "SceneInput.hpp"

namespace py = pybind11;

namespace coulomb::python {
namespace {

engine::WorldQueries& queriesOf(PyWorld& w) {
  use(w);  // refuses while another thread steps the world
  if (!w.queries) w.queries.emplace(w.world);
  return *w.queries;
}

geometry::QueryFilter filterOf(std::uint32_t category, std::uint32_t mask) {
  geometry::QueryFilter filter;
  filter.bits.category = category;
  filter.bits.mask = mask;
  return filter;
}

std::shared_ptr<const geometry::Shape> shapeOf(const py::dict& desc) {
  return std::make_shared<const geometry::Shape>(shapeDescFrom(desc, "query shape").shape);
}

// RayHit and ShapeHit share their fields: one dict for both.
template <class Hit>
py::dict hitDict(const Hit& hit) {
  py::dict d;
  d["body"] = handleOf(hit.body);
  d["collider"] = handleOf(hit.collider);
  d["point"] = toNumpy(Eigen::VectorXd(hit.point));
  d["normal"] = toNumpy(Eigen::VectorXd(hit.normal));
  d["fraction"] = hit.fraction;
  return d;
}

py::list colliderList(const std::vector<geometry::ColliderId>& ids, const engine::World& world) {
  py::list out;
  for (geometry::ColliderId id : ids) {
    py::dict d;
    d["body"] = handleOf(world.collider(id).body);
    d["collider"] = handleOf(id);
    out.append(d);
  }
  return out;
}

}  // namespace

void bindQueries(py::module_& m) {
  auto world =
      py::reinterpret_borrow<py::class_<PyWorld, std::shared_ptr<PyWorld>>>(m.attr("World"));
  constexpr std::uint32_t kAll = std::numeric_limits<std::uint32_t>::max();
  world
      .def(
          "cast_ray",
          [](PyWorld& w, const py::object& origin, const py::object& translation,
             std::uint32_t category, std::uint32_t mask) -> py::object {
            const auto hit = queriesOf(w).castRay(toVector(origin, "origin", 3),
                                                  toVector(translation, "translation", 3),
                                                  filterOf(category, mask));
            if (!hit) return py::none();
            return hitDict(*hit);
          },
          py::arg("origin"), py::arg("translation"), py::kw_only(), py::arg("category") = 1u,
          py::arg("mask") = kAll,
          "the first hit of the segment origin -> origin + translation: a dict (body, collider, "
          "point, normal, fraction) or None")
      .def(
          "cast_ray_all",
          [](PyWorld& w, const py::object& origin, const py::object& translation,
             std::uint32_t category, std::uint32_t mask) {
            py::list out;
            for (const geometry::RayHit& hit : queriesOf(w).castRayAll(
                     toVector(origin, "origin", 3), toVector(translation, "translation", 3),
                     filterOf(category, mask)))
              out.append(hitDict(hit));
            return out;
          },
          py::arg("origin"), py::arg("translation"), py::kw_only(), py::arg("category") = 1u,
          py::arg("mask") = kAll, "every collider the segment meets, by fraction")
      .def(
          "cast_shape",
          [](PyWorld& w, const py::dict& shape, const py::object& start,
             const py::object& translation, const py::object& rotation, std::uint32_t category,
             std::uint32_t mask) -> py::object {
            const auto hit = queriesOf(w).castShape(shapeOf(shape), poseFrom(start, rotation),
                                                    toVector(translation, "translation", 3),
                                                    filterOf(category, mask));
            if (!hit) return py::none();
            return hitDict(*hit);
          },
          py::arg("shape"), py::arg("start"), py::arg("translation"), py::kw_only(),
          py::arg("rotation") = py::none(), py::arg("category") = 1u, py::arg("mask") = kAll,
          "sweeps a shape (JSON scene format: sphere, box, capsule, cylinder, convex_hull) from "
          "start by translation: its first hit as a dict (body, collider, point, normal, "
          "fraction) or None")
      .def(
          "overlap",
          [](PyWorld& w, const py::dict& shape, const py::object& position,
             const py::object& rotation, std::uint32_t category, std::uint32_t mask) {
            engine::WorldQueries& q = queriesOf(w);
            return colliderList(
                q.overlap(shapeOf(shape), poseFrom(position, rotation), filterOf(category, mask)),
                w.world);
          },
          py::arg("shape"), py::arg("position"), py::kw_only(), py::arg("rotation") = py::none(),
          py::arg("category") = 1u, py::arg("mask") = kAll,
          "the colliders a shape at a pose overlaps: a list of dicts (body, collider)")
      .def(
          "query_aabb",
          [](PyWorld& w, const py::object& lower, const py::object& upper, std::uint32_t category,
             std::uint32_t mask) {
            engine::WorldQueries& q = queriesOf(w);
            const geometry::Aabb box{toVector(lower, "lower", 3), toVector(upper, "upper", 3)};
            return colliderList(q.queryAabb(box, filterOf(category, mask)), w.world);
          },
          py::arg("lower"), py::arg("upper"), py::kw_only(), py::arg("category") = 1u,
          py::arg("mask") = kAll,
          "the colliders whose world AABB overlaps [lower, upper]: a list of dicts (body, "
          "collider)")
      .def(
          "closest_points",
          [](PyWorld& w, std::int64_t a, std::int64_t b) {
            const geometry::BodyId ia = idOf<geometry::BodyId>(w, a, "body");
            const geometry::BodyId ib = idOf<geometry::BodyId>(w, b, "body");
            engine::WorldQueries& q = queriesOf(w);
            std::optional<geometry::ClosestPoints> best;
            for (const geometry::Collider& ca : w.world.colliders())
              for (const geometry::Collider& cb : w.world.colliders())
                if (ca.body == ia && cb.body == ib) {
                  const geometry::ClosestPoints p = q.closestPoints(ca.id, cb.id);
                  if (!best || p.distance < best->distance) best = p;
                }
            if (!best) throw engine::CoulombError("closest_points: a body has no collider");
            return py::make_tuple(best->distance, toNumpy(Eigen::VectorXd(best->pointA)),
                                  toNumpy(Eigen::VectorXd(best->pointB)));
          },
          py::arg("body_a"), py::arg("body_b"),
          "(distance [m], point on a, point on b) over the bodies' colliders; a negative "
          "distance is a penetration depth");
}

}  // namespace coulomb::python
