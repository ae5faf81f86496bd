#include <coulomb/geometry/ManifoldBuilder.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>

namespace coulomb::geometry {
namespace {

// Strictly better score, or an equal score (within a relative 1e-12) and a lower feature id.
bool better(double score, std::uint32_t id, double bestScore, std::uint32_t bestId) {
  const double tol = 1e-12 * std::max(1.0, std::abs(bestScore));
  if (score > bestScore + tol) return true;
  return score >= bestScore - tol && id < bestId;
}

}  // namespace

void reduceToFour(const Eigen::Vector3d& normal, std::vector<ContactCandidate>& points) {
  if (points.size() <= 4) {
    std::sort(points.begin(), points.end(),
              [](const auto& l, const auto& r) { return l.featureId < r.featureId; });
    return;
  }
  const std::size_t none = points.size();
  auto pick = [&](auto score) {
    std::size_t best = none;
    double bestScore = -1e300;
    for (std::size_t i = 0; i < points.size(); ++i) {
      const double s = score(points[i].position);
      if (std::isnan(s)) continue;
      if (best == none || better(s, points[i].featureId, bestScore, points[best].featureId)) {
        best = i;
        bestScore = s;
      }
    }
    return best;
  };
  // 1. deepest point (score: depth).
  std::size_t i0 = none;
  for (std::size_t i = 0; i < points.size(); ++i)
    if (i0 == none ||
        better(points[i].depth, points[i].featureId, points[i0].depth, points[i0].featureId))
      i0 = i;
  const Eigen::Vector3d p0 = points[i0].position;
  // 2. farthest from p0.
  const std::size_t i1 = pick([&](const Eigen::Vector3d& p) { return (p - p0).squaredNorm(); });
  const Eigen::Vector3d p1 = points[i1].position;
  // 3. largest triangle area |(p1-p0) x (p-p0) . n|, with its sign remembered.
  const std::size_t i2 =
      pick([&](const Eigen::Vector3d& p) { return std::abs((p1 - p0).cross(p - p0).dot(normal)); });
  const Eigen::Vector3d p2 = points[i2].position;
  // 4. most area added outside triangle p0 p1 p2: the most negative signed edge area, measured
  // with the triangle oriented counter-clockwise about the normal.
  const double orientation = (p1 - p0).cross(p2 - p0).dot(normal) >= 0.0 ? 1.0 : -1.0;
  auto outside = [&](const Eigen::Vector3d& p) {
    const double e01 = orientation * (p1 - p0).cross(p - p0).dot(normal);
    const double e12 = orientation * (p2 - p1).cross(p - p1).dot(normal);
    const double e20 = orientation * (p0 - p2).cross(p - p2).dot(normal);
    return -std::min({e01, e12, e20});
  };
  // At most four chosen points, in fixed storage; written back over `points` (its capacity stays:
  // the narrow phase reuses it for every pair).
  std::array<std::size_t, 4> chosen{i0, i1, i2, none};
  std::size_t chosenCount = 3;
  std::size_t i3 = none;
  double best3 = 0.0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (std::find(chosen.begin(), chosen.begin() + 3, i) != chosen.begin() + 3) continue;
    const double s = outside(points[i].position);
    if (s <= 1e-14) continue;
    if (i3 == none || better(s, points[i].featureId, best3, points[i3].featureId)) {
      i3 = i;
      best3 = s;
    }
  }
  if (i3 != none) chosen[chosenCount++] = i3;
  // Insertion sorts of at most four entries (std::sort on part of a std::array trips GCC's
  // array-bounds analysis).
  const auto sortFirst = [](auto& entries, std::size_t count, auto less) {
    for (std::size_t i = 1; i < count; ++i)
      for (std::size_t j = i; j > 0 && less(entries[j], entries[j - 1]); --j)
        std::swap(entries[j], entries[j - 1]);
  };
  sortFirst(chosen, chosenCount, std::less<>());
  std::size_t unique = 0;
  for (std::size_t k = 0; k < chosenCount; ++k)
    if (unique == 0 || chosen[k] != chosen[unique - 1]) chosen[unique++] = chosen[k];
  chosenCount = unique;
  std::array<ContactCandidate, 4> kept;
  for (std::size_t k = 0; k < chosenCount; ++k) kept[k] = points[chosen[k]];
  sortFirst(kept, chosenCount,
            [](const auto& l, const auto& r) { return l.featureId < r.featureId; });
  points.resize(chosenCount);
  std::copy(kept.begin(), kept.begin() + static_cast<std::ptrdiff_t>(chosenCount), points.begin());
}

void clipPolygon(ClipPolygon& polygon, const Eigen::Vector3d& axis, double limit,
                 std::uint32_t plane) {
  const std::size_t n = polygon.size();
  if (n == 0) return;
  ClipPolygon out;
  for (std::size_t i = 0; i < n; ++i) {
    const ClipVertex& a = polygon[i];
    const ClipVertex& b = polygon[(i + 1) % n];
    const double da = axis.dot(a.position) - limit;
    const double db = axis.dot(b.position) - limit;
    if (da <= 0.0) out.vertices[out.count++] = a;
    if ((da < 0.0 && db > 0.0) || (da > 0.0 && db < 0.0)) {
      const double t = da / (da - db);
      // The segment a->b is an original edge (numbered by its first vertex, 0..3) or lies on an
      // earlier clip line q (code 4 + q); a segment crosses a line once, so ids are unique.
      const std::uint32_t segment = (a.id & 0x100u) ? 4u + ((a.id >> 4) & 0x3u) : (a.id & 0x3u);
      out.vertices[out.count++] = {a.position + t * (b.position - a.position),
                                   0x100u | ((plane & 0x3u) << 4) | segment};
    }
  }
  polygon = out;
}

ContactManifold finishManifold(PairContact& raw, const Collider& a, const Collider& b,
                               const Pose& bodyPoseA, const Pose& bodyPoseB) {
  ContactManifold m;
  m.colliderA = a.id;
  m.colliderB = b.id;
  m.bodyA = a.body;
  m.bodyB = b.body;
  m.normal = raw.normal.normalized();
  makeTangentFrame(m.normal, m.tangent1, m.tangent2);
  m.friction = std::sqrt(std::max(0.0, a.material.friction * b.material.friction));
  m.restitution = std::max(a.material.restitution, b.material.restitution);
  m.sensor = a.sensor || b.sensor;
  reduceToFour(m.normal, raw.points);
  m.pointCount = static_cast<int>(raw.points.size());
  for (int i = 0; i < m.pointCount; ++i) {
    ContactPoint& p = m.points[static_cast<std::size_t>(i)];
    p.position = raw.points[static_cast<std::size_t>(i)].position;
    p.depth = raw.points[static_cast<std::size_t>(i)].depth;
    p.featureId = raw.points[static_cast<std::size_t>(i)].featureId;
    p.localA = bodyPoseA.applyInverse(p.position);
    p.localB = bodyPoseB.applyInverse(p.position);
  }
  return m;
}

}  // namespace coulomb::geometry
