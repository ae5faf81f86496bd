#include <coulomb/geometry/HullContacts.hpp>

#include <coulomb/geometry/PrimitiveContacts.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <utility>

namespace coulomb::geometry {
namespace {

// Prefer a face of `a` over a face of `b`, and faces over edges, unless the other is clearly
// better, so the chosen features (and the feature ids) stay fixed under tiny motions (the same
// tolerances as BoxContacts).
constexpr double kFaceTolerance = 1e-5;  // [m]
constexpr double kEdgeTolerance = 1e-4;  // [m]
constexpr double kClipSlop = 2e-3;       // relative to the reference face's inradius

struct Face {
  Eigen::Vector3d normal;  // outward, unit
  double offset = 0.0;     // normal . x = offset on the face plane
  std::vector<int> loop;   // vertex indices, counter-clockwise seen from outside
};

struct Polytope {
  std::vector<Eigen::Vector3d> vertices;  // world
  std::vector<Face> faces;
  std::vector<std::pair<int, int>> edges;  // unique, i < j
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
};

// Orders the vertices of a planar convex face counter-clockwise about its normal.
void orderLoop(const std::vector<Eigen::Vector3d>& vertices, Face& face) {
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  for (const int i : face.loop) centre += vertices[i];
  centre /= static_cast<double>(face.loop.size());
  const Eigen::Vector3d u = face.normal.unitOrthogonal();
  const Eigen::Vector3d w = face.normal.cross(u);
  std::vector<std::pair<double, int>> byAngle;
  for (const int i : face.loop) {
    const Eigen::Vector3d r = vertices[i] - centre;
    byAngle.emplace_back(std::atan2(w.dot(r), u.dot(r)), i);
  }
  std::sort(byAngle.begin(), byAngle.end());
  face.loop.clear();
  for (const auto& entry : byAngle) face.loop.push_back(entry.second);
}

void finishPolytope(Polytope& p) {
  p.centroid = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& v : p.vertices) p.centroid += v;
  p.centroid /= static_cast<double>(p.vertices.size());
  for (Face& face : p.faces) {
    orderLoop(p.vertices, face);
    for (std::size_t k = 0; k < face.loop.size(); ++k) {
      const int i = face.loop[k], j = face.loop[(k + 1) % face.loop.size()];
      p.edges.emplace_back(std::min(i, j), std::max(i, j));
    }
  }
  std::sort(p.edges.begin(), p.edges.end());
  p.edges.erase(std::unique(p.edges.begin(), p.edges.end()), p.edges.end());
}

// Faces of a hull: its triangles merged by plane (qhull triangulates every polygonal face).
Polytope hullPolytope(const ConvexHull& hull, const Pose& pose) {
  Polytope p;
  p.vertices.reserve(hull.vertices.size());
  double scale = 0.0;
  for (const Eigen::Vector3d& v : hull.vertices) {
    p.vertices.push_back(pose.apply(v));
    scale = std::max(scale, v.cwiseAbs().maxCoeff());
  }
  const double planeTolerance = 1e-9 * std::max(scale, 1e-3);
  for (const Eigen::Vector3i& t : hull.triangles) {
    const Eigen::Vector3d& a = p.vertices[t[0]];
    const Eigen::Vector3d n = (p.vertices[t[1]] - a).cross(p.vertices[t[2]] - a);
    if (n.norm() <= 0.0) continue;  // degenerate triangle
    const Eigen::Vector3d normal = n.normalized();
    const double offset = normal.dot(a);
    auto same = std::find_if(p.faces.begin(), p.faces.end(), [&](const Face& f) {
      return f.normal.dot(normal) > 1.0 - 1e-10 && std::abs(f.offset - offset) < planeTolerance;
    });
    if (same == p.faces.end()) {
      p.faces.push_back({normal, offset, {}});
      same = std::prev(p.faces.end());
    }
    for (int k = 0; k < 3; ++k)
      if (std::find(same->loop.begin(), same->loop.end(), t[k]) == same->loop.end())
        same->loop.push_back(t[k]);
  }
  finishPolytope(p);
  return p;
}

Polytope boxPolytope(const Box& box, const Pose& pose) {
  Polytope p;
  const Eigen::Matrix3d axes = pose.rotationMatrix();
  for (int c = 0; c < 8; ++c) {
    Eigen::Vector3d v = pose.position;
    for (int k = 0; k < 3; ++k) v += ((c >> k) & 1 ? 1.0 : -1.0) * box.halfExtents[k] * axes.col(k);
    p.vertices.push_back(v);
  }
  for (int k = 0; k < 3; ++k)
    for (const int side : {1, 0}) {
      Face face;
      face.normal = (side ? 1.0 : -1.0) * axes.col(k);
      face.offset = face.normal.dot(pose.position) + box.halfExtents[k];
      for (int c = 0; c < 8; ++c)
        if (((c >> k) & 1) == side) face.loop.push_back(c);
      p.faces.push_back(std::move(face));
    }
  finishPolytope(p);
  return p;
}

double minAlong(const Polytope& p, const Eigen::Vector3d& axis) {
  double lowest = std::numeric_limits<double>::infinity();
  for (const Eigen::Vector3d& v : p.vertices) lowest = std::min(lowest, axis.dot(v));
  return lowest;
}

// Largest separation of `other` from the face planes of `p` (> 0: a gap of that size).
std::pair<double, int> faceSeparation(const Polytope& p, const Polytope& other) {
  std::pair<double, int> best{-std::numeric_limits<double>::infinity(), -1};
  for (std::size_t f = 0; f < p.faces.size(); ++f) {
    const double sep = minAlong(other, p.faces[f].normal) - p.faces[f].offset;
    if (sep > best.first) best = {sep, static_cast<int>(f)};
  }
  return best;
}

struct EdgeAxis {
  double separation = -std::numeric_limits<double>::infinity();
  int edgeA = -1, edgeB = -1;
  Eigen::Vector3d axis = Eigen::Vector3d::Zero();  // from a to b
};

// Cross products of edge pairs. Each pair's axis is oriented away from a's centroid, and its
// separation is measured with the support functions of both polytopes (a valid bound for any
// axis); the winning pair is then the pair of supporting edges.
EdgeAxis edgeSeparation(const Polytope& a, const Polytope& b) {
  EdgeAxis best;
  for (std::size_t i = 0; i < a.edges.size(); ++i) {
    const Eigen::Vector3d& a0 = a.vertices[a.edges[i].first];
    const Eigen::Vector3d da = a.vertices[a.edges[i].second] - a0;
    for (std::size_t j = 0; j < b.edges.size(); ++j) {
      const Eigen::Vector3d& b0 = b.vertices[b.edges[j].first];
      const Eigen::Vector3d db = b.vertices[b.edges[j].second] - b0;
      Eigen::Vector3d axis = da.cross(db);
      const double length = axis.norm();
      if (length < 1e-6 * da.norm() * db.norm()) continue;  // parallel: covered by face axes
      axis /= length;
      if (axis.dot(a0 - a.centroid) < 0.0) axis = -axis;
      // Only supporting edges: a's edge must be extreme along the axis on a, b's on b.
      const double onA = axis.dot(a0);
      const double onB = axis.dot(b0);
      const double sep = onB - onA;
      if (sep <= best.separation) continue;
      if (onA < -minAlong(a, -axis) - 1e-9 || onB > minAlong(b, axis) + 1e-9) continue;
      best = {sep, static_cast<int>(i), static_cast<int>(j), axis};
    }
  }
  return best;
}

// The incident face of `inc` clipped against the side planes of face `refFace` of `ref`.
void faceContact(const Polytope& ref, int refFace, const Polytope& inc, bool refIsB, double margin,
                 PairContact& out) {
  const Face& r = ref.faces[refFace];
  int incFace = 0;
  double mostOpposed = std::numeric_limits<double>::infinity();
  for (std::size_t f = 0; f < inc.faces.size(); ++f) {
    const double d = inc.faces[f].normal.dot(r.normal);
    if (d < mostOpposed) mostOpposed = d, incFace = static_cast<int>(f);
  }
  const Face& incident = inc.faces[incFace];
  std::vector<ClipVertex> polygon;
  for (std::size_t k = 0; k < incident.loop.size(); ++k)
    polygon.push_back({inc.vertices[incident.loop[k]], static_cast<std::uint32_t>(k & 0x7f)});

  struct SidePlane {
    Eigen::Vector3d normal;
    double limit;
  };
  std::vector<SidePlane> sides;
  const std::size_t n = r.loop.size();
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  for (const int i : r.loop) centre += ref.vertices[i];
  centre /= static_cast<double>(n);
  double inradius = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < n; ++k) {
    const Eigen::Vector3d& p0 = ref.vertices[r.loop[k]];
    const Eigen::Vector3d edge = ref.vertices[r.loop[(k + 1) % n]] - p0;
    const Eigen::Vector3d side = edge.cross(r.normal).normalized();  // outward for a CCW loop
    sides.push_back({side, side.dot(p0)});
    inradius = std::min(inradius, sides.back().limit - side.dot(centre));
  }
  // Side planes pushed out by a slop (as BoxContacts: kClipSlop times the face's half size), so
  // flush faces keep their corners, and their ids, under tiny rotations.
  const double slop = kClipSlop * inradius;
  for (std::size_t k = 0; k < n; ++k) {
    const Eigen::Vector3d& side = sides[k].normal;
    // Clip ids as ManifoldBuilder's clipPolygon, on a wider field: 0x800 | plane << 4 | segment.
    std::vector<ClipVertex> clipped;
    for (std::size_t v = 0; v < polygon.size(); ++v) {
      const ClipVertex& a = polygon[v];
      const ClipVertex& b = polygon[(v + 1) % polygon.size()];
      const double da = side.dot(a.position) - sides[k].limit - slop;
      const double db = side.dot(b.position) - sides[k].limit - slop;
      if (da <= 0.0) clipped.push_back(a);
      if ((da < 0.0 && db > 0.0) || (da > 0.0 && db < 0.0)) {
        const std::uint32_t segment = a.id & 0x800u ? 0x40u | ((a.id >> 4) & 0x3fu) : a.id & 0x3fu;
        clipped.push_back(
            {a.position + da / (da - db) * (b.position - a.position),
             0x800u | (static_cast<std::uint32_t>(k & 0x7f) << 4) | (segment & 0xfu)});
      }
    }
    polygon = std::move(clipped);
    if (polygon.empty()) return;
  }
  const std::uint32_t base = (refIsB ? 1u << 31 : 0u) |
                             (static_cast<std::uint32_t>(refFace & 0xff) << 20) |
                             (static_cast<std::uint32_t>(incFace & 0xff) << 12);
  out.normal = refIsB ? Eigen::Vector3d(-r.normal) : r.normal;
  for (const ClipVertex& p : polygon) {
    const double gap = r.normal.dot(p.position) - r.offset;
    if (gap > margin) continue;
    // Back inside the reference face (undoes the slop), then midway between the two faces.
    Eigen::Vector3d q = p.position - gap * r.normal;
    for (const SidePlane& s : sides) {
      const double outside = s.normal.dot(q) - s.limit;
      if (outside > 0.0) q -= outside * s.normal;
    }
    out.points.push_back({q + 0.5 * gap * r.normal, -gap, base | (p.id & 0xfffu)});
  }
}

int polytopeContact(const Polytope& a, const Polytope& b, double margin, PairContact& out) {
  const auto [sepA, faceA] = faceSeparation(a, b);
  const auto [sepB, faceB] = faceSeparation(b, a);
  if (faceA < 0 || faceB < 0) return -1;
  if (std::max(sepA, sepB) > margin) return 0;
  const EdgeAxis edge = edgeSeparation(a, b);
  if (edge.separation > margin) return 0;
  const double bestFace = std::max(sepA, sepB);
  if (edge.edgeA >= 0 && edge.separation > bestFace + kEdgeTolerance) {
    const auto [a0, a1] = a.edges[edge.edgeA];
    const auto [b0, b1] = b.edges[edge.edgeB];
    Eigen::Vector3d ca, cb;
    closestSegmentPoints(a.vertices[a0], a.vertices[a1], b.vertices[b0], b.vertices[b1], ca, cb);
    const double gap = edge.axis.dot(cb - ca);
    if (gap > margin) return 0;
    out.normal = edge.axis;
    out.points.push_back({0.5 * (ca + cb), -gap,
                          (1u << 30) | (static_cast<std::uint32_t>(edge.edgeA & 0x3ffff) << 12) |
                              static_cast<std::uint32_t>(edge.edgeB & 0xfff)});
    return 1;
  }
  if (sepB > sepA + kFaceTolerance)
    faceContact(b, faceB, a, /*refIsB=*/true, margin, out);
  else
    faceContact(a, faceA, b, /*refIsB=*/false, margin, out);
  return out.points.empty() ? 0 : 1;
}

bool tooLarge(const ConvexHull& hull) {
  return hull.vertices.size() > kMaxClippedHullVertices || hull.triangles.empty();
}

}  // namespace

int hullHull(const ConvexHull& a, const Pose& pa, const ConvexHull& b, const Pose& pb,
             double margin, PairContact& out) {
  if (tooLarge(a) || tooLarge(b)) return -1;
  return polytopeContact(hullPolytope(a, pa), hullPolytope(b, pb), margin, out);
}

int boxHull(const Box& a, const Pose& pa, const ConvexHull& b, const Pose& pb, double margin,
            PairContact& out) {
  if (tooLarge(b)) return -1;
  return polytopeContact(boxPolytope(a, pa), hullPolytope(b, pb), margin, out);
}

}  // namespace coulomb::geometry
