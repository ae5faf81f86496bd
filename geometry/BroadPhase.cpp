#include <coulomb/geometry/BroadPhase.hpp>

#include <coulomb/geometry/PrimitiveContacts.hpp>

#include <algorithm>
#include <stdexcept>
#include <unordered_map>

namespace coulomb::geometry {

std::vector<CandidatePair> BroadPhase::update(const std::vector<Collider>& colliders,
                                              std::span<const Pose> shapePoses,
                                              std::vector<char>& usable, FclScene& scene,
                                              double margin, const PairPredicate& keep,
                                              std::vector<CollisionFailure>& failures,
                                              std::span<const double> sweeps) {
  auto sweepOf = [&](std::size_t i) { return i < sweeps.size() ? sweeps[i] : 0.0; };
  std::unordered_map<ColliderId, std::size_t> indexOf;
  indexOf.reserve(colliders.size());
  std::vector<std::size_t> planes, solids;
  for (std::size_t i = 0; i < colliders.size(); ++i) {
    if (!usable[i]) continue;
    const Collider& c = colliders[i];
    try {
      scene.upsert(c.id, c.shape);
      scene.setPose(c.id, shapePoses[i], sweepOf(i));
    } catch (const std::exception& e) {
      failures.push_back({c.id, ColliderId{}, e.what()});
      usable[i] = 0;
      scene.erase(c.id);
      continue;
    }
    indexOf.emplace(c.id, i);
    (std::holds_alternative<Plane>(*c.shape) ? planes : solids).push_back(i);
  }
  for (const ColliderId id : scene.ids())  // colliders removed since the last step
    if (!indexOf.count(id)) scene.erase(id);
  scene.updateTree();

  std::vector<std::pair<ColliderId, ColliderId>> ids = scene.overlappingPairs();  // sorted
  const auto treePairs = static_cast<std::ptrdiff_t>(ids.size());
  // Planes: one AABB-against-half-space test per solid (cheap; the tree cannot hold planes).
  for (std::size_t p : planes) {
    const WorldPlane plane = toWorld(std::get<Plane>(*colliders[p].shape), shapePoses[p]);
    for (std::size_t s : solids) {
      const Aabb box = scene.worldAabb(colliders[s].id);
      const Eigen::Vector3d centre = 0.5 * (box.min + box.max), half = 0.5 * (box.max - box.min);
      const double lowest = plane.normal.dot(centre) - plane.normal.cwiseAbs().dot(half);
      if (lowest - plane.offset <= margin + sweepOf(p))  // the box holds the solid's sweep
        ids.emplace_back(std::min(colliders[p].id, colliders[s].id),
                         std::max(colliders[p].id, colliders[s].id));
    }
  }
  std::sort(ids.begin() + treePairs, ids.end());
  std::inplace_merge(ids.begin(), ids.begin() + treePairs, ids.end());
  std::vector<CandidatePair> pairs;
  pairs.reserve(ids.size());
  for (const auto& [ia, ib] : ids) {
    const std::size_t a = indexOf.at(ia), b = indexOf.at(ib);
    const Collider& ca = colliders[a];
    const Collider& cb = colliders[b];
    if (ca.body == cb.body) continue;
    if (!ca.filter.accepts(cb.filter)) continue;
    if (keep && !keep(ca, cb)) continue;
    pairs.push_back({a, b});
  }
  return pairs;
}

}  // namespace coulomb::geometry
