#include <coulomb/geometry/BroadPhase.hpp>

#include <coulomb/geometry/PrimitiveContacts.hpp>

#include <algorithm>
#include <stdexcept>

namespace coulomb::geometry {
namespace {
constexpr std::size_t kNoCollider = static_cast<std::size_t>(-1);
}  // namespace

std::size_t BroadPhase::indexOf(ColliderId id) const {
  if (id.index < indexBySlot_.size() && indexBySlot_[id.index].second == id.generation &&
      indexBySlot_[id.index].first != kNoCollider)
    return indexBySlot_[id.index].first;
  const auto it =
      std::lower_bound(indexById_.begin(), indexById_.end(), id,
                       [](const auto& entry, ColliderId key) { return entry.first < key; });
  if (it == indexById_.end() || it->first != id)
    throw std::logic_error("BroadPhase: the tree returned a collider it was not given");
  return it->second;
}

const std::vector<CandidatePair>& BroadPhase::update(const std::vector<Collider>& colliders,
                                                     std::span<const Pose> shapePoses,
                                                     std::vector<char>& usable, FclScene& scene,
                                                     double margin, const PairPredicate& keep,
                                                     std::vector<CollisionFailure>& failures,
                                                     std::span<const double> sweeps) {
  auto sweepOf = [&](std::size_t i) { return i < sweeps.size() ? sweeps[i] : 0.0; };
  indexById_.clear();
  planes_.clear();
  solids_.clear();
  std::vector<std::size_t>& planes = planes_;
  std::vector<std::size_t>& solids = solids_;
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
    indexById_.emplace_back(c.id, i);
    (std::holds_alternative<Plane>(*c.shape) ? planes : solids).push_back(i);
  }
  std::sort(indexById_.begin(), indexById_.end());
  // A table by slot when the slots are dense (at most twice the colliders, plus a little): one
  // look-up per pair's collider instead of a binary search.
  indexBySlot_.clear();
  const std::uint32_t slots = indexById_.empty() ? 0 : indexById_.back().first.index + 1;
  if (!indexById_.empty() && indexById_.back().first.valid() &&
      slots <= 2 * indexById_.size() + 64) {
    indexBySlot_.assign(slots, {kNoCollider, 0});
    for (const auto& [id, i] : indexById_) indexBySlot_[id.index] = {i, id.generation};
  }
  if (scene.size() != indexById_.size())  // colliders removed since the last step
    for (const ColliderId id : scene.ids())
      if (!std::binary_search(indexById_.begin(), indexById_.end(), std::pair{id, std::size_t{0}},
                              [](const auto& l, const auto& r) { return l.first < r.first; }))
        scene.erase(id);
  scene.updateTree();

  std::vector<std::pair<ColliderId, ColliderId>>& ids = ids_;
  scene.overlappingPairs(ids);  // sorted
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
  // One sort of the whole list (the tree's part is already sorted): std::inplace_merge would
  // allocate a buffer on every step.
  if (static_cast<std::ptrdiff_t>(ids.size()) > treePairs) std::sort(ids.begin(), ids.end());
  std::vector<CandidatePair>& pairs = pairs_;
  pairs.clear();
  for (const auto& [ia, ib] : ids) {
    const std::size_t a = indexOf(ia), b = indexOf(ib);
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
