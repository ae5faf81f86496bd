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

// Orders the vertices of a planar convex face counter-clockwise about its normal.
void orderLoop(const std::vector<Eigen::Vector3d>& vertices, HullFace& face) {
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

// Loops ordered, edges listed from them (unique, sorted).
void finishFaces(const std::vector<Eigen::Vector3d>& vertices, std::vector<HullFace>& faces,
                 std::vector<std::pair<int, int>>& edges) {
  edges.clear();
  for (HullFace& face : faces) {
    orderLoop(vertices, face);
    for (std::size_t k = 0; k < face.loop.size(); ++k) {
      const int i = face.loop[k], j = face.loop[(k + 1) % face.loop.size()];
      edges.emplace_back(std::min(i, j), std::max(i, j));
    }
  }
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
}

void setCentroid(WorldPolytope& p) {
  p.centroid = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& v : p.vertices) p.centroid += v;
  p.centroid /= static_cast<double>(p.vertices.size());
}

// The hull moved to the world; its faces and edges are the shape's (or, for a hull made without
// makeConvexHull, built into `faceless`).
void hullPolytope(const ConvexHull& hull, const Pose& pose, ConvexHull& faceless,
                  WorldPolytope& p) {
  const ConvexHull* shape = &hull;
  if (hull.faces.empty()) {
    faceless.vertices = hull.vertices;
    faceless.triangles = hull.triangles;
    buildHullFaces(faceless);
    shape = &faceless;
  }
  p.vertices.resize(hull.vertices.size());
  for (std::size_t i = 0; i < hull.vertices.size(); ++i)
    p.vertices[i] = pose.apply(hull.vertices[i]);
  const Eigen::Matrix3d rotation = pose.rotationMatrix();
  p.normals.resize(shape->faces.size());
  p.offsets.resize(shape->faces.size());
  for (std::size_t f = 0; f < shape->faces.size(); ++f) {
    p.normals[f] = rotation * shape->faces[f].normal;
    p.offsets[f] = shape->faces[f].offset + p.normals[f].dot(pose.position);
  }
  p.faces = &shape->faces;
  p.edges = &shape->edges;
  setCentroid(p);
}

void boxPolytope(const Box& box, const Pose& pose, ConvexHull& topology, WorldPolytope& p) {
  if (topology.faces.empty()) {  // faces +x, -x, +y, -y, +z, -z of the unit cube's corners
    const auto corners = boxCorners(Box{Eigen::Vector3d::Ones()}, Pose::identity());
    topology.vertices.assign(corners.begin(), corners.end());  // corner c: bit k set = +axis k
    for (int k = 0; k < 3; ++k)
      for (const int side : {1, 0}) {
        HullFace face;
        face.normal = (side ? 1.0 : -1.0) * Eigen::Vector3d::Unit(k);
        face.offset = 1.0;
        for (int c = 0; c < 8; ++c)
          if (((c >> k) & 1) == side) face.loop.push_back(c);
        topology.faces.push_back(std::move(face));
      }
    finishFaces(topology.vertices, topology.faces, topology.edges);
  }
  const Eigen::Matrix3d axes = pose.rotationMatrix();
  p.vertices.resize(8);
  for (int c = 0; c < 8; ++c) {
    Eigen::Vector3d v = pose.position;
    for (int k = 0; k < 3; ++k) v += ((c >> k) & 1 ? 1.0 : -1.0) * box.halfExtents[k] * axes.col(k);
    p.vertices[static_cast<std::size_t>(c)] = v;
  }
  p.normals.resize(6);
  p.offsets.resize(6);
  for (int k = 0; k < 3; ++k)
    for (const int side : {1, 0}) {
      const auto f = static_cast<std::size_t>(2 * k + (1 - side));
      p.normals[f] = (side ? 1.0 : -1.0) * axes.col(k);
      p.offsets[f] = p.normals[f].dot(pose.position) + box.halfExtents[k];
    }
  p.faces = &topology.faces;
  p.edges = &topology.edges;
  setCentroid(p);
}

double minAlong(const WorldPolytope& p, const Eigen::Vector3d& axis) {
  double lowest = std::numeric_limits<double>::infinity();
  for (const Eigen::Vector3d& v : p.vertices) lowest = std::min(lowest, axis.dot(v));
  return lowest;
}

// Largest separation of `other` from the face planes of `p` (> 0: a gap of that size).
std::pair<double, int> faceSeparation(const WorldPolytope& p, const WorldPolytope& other) {
  std::pair<double, int> best{-std::numeric_limits<double>::infinity(), -1};
  for (std::size_t f = 0; f < p.normals.size(); ++f) {
    const double sep = minAlong(other, p.normals[f]) - p.offsets[f];
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
EdgeAxis edgeSeparation(const WorldPolytope& a, const WorldPolytope& b) {
  EdgeAxis best;
  const std::vector<std::pair<int, int>>& edgesA = *a.edges;
  const std::vector<std::pair<int, int>>& edgesB = *b.edges;
  for (std::size_t i = 0; i < edgesA.size(); ++i) {
    const Eigen::Vector3d& a0 = a.vertices[edgesA[i].first];
    const Eigen::Vector3d da = a.vertices[edgesA[i].second] - a0;
    for (std::size_t j = 0; j < edgesB.size(); ++j) {
      const Eigen::Vector3d& b0 = b.vertices[edgesB[j].first];
      const Eigen::Vector3d db = b.vertices[edgesB[j].second] - b0;
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
void faceContact(const WorldPolytope& ref, int refFace, const WorldPolytope& inc, bool refIsB,
                 double margin, PairContact& out, HullScratch& scratch) {
  const Eigen::Vector3d& refNormal = ref.normals[refFace];
  const double refOffset = ref.offsets[refFace];
  const std::vector<int>& refLoop = (*ref.faces)[refFace].loop;
  int incFace = 0;
  double mostOpposed = std::numeric_limits<double>::infinity();
  for (std::size_t f = 0; f < inc.normals.size(); ++f) {
    const double d = inc.normals[f].dot(refNormal);
    if (d < mostOpposed) mostOpposed = d, incFace = static_cast<int>(f);
  }
  const std::vector<int>& incidentLoop = (*inc.faces)[incFace].loop;
  std::vector<ClipVertex>& polygon = scratch.polygon;
  polygon.clear();
  for (std::size_t k = 0; k < incidentLoop.size(); ++k)
    polygon.push_back({inc.vertices[incidentLoop[k]], static_cast<std::uint32_t>(k & 0x7f)});

  std::vector<Eigen::Vector3d>& sideNormals = scratch.sideNormals;
  std::vector<double>& sideLimits = scratch.sideLimits;
  sideNormals.clear();
  sideLimits.clear();
  const std::size_t n = refLoop.size();
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  for (const int i : refLoop) centre += ref.vertices[i];
  centre /= static_cast<double>(n);
  double inradius = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < n; ++k) {
    const Eigen::Vector3d& p0 = ref.vertices[refLoop[k]];
    const Eigen::Vector3d edge = ref.vertices[refLoop[(k + 1) % n]] - p0;
    const Eigen::Vector3d side = edge.cross(refNormal).normalized();  // outward for a CCW loop
    sideNormals.push_back(side);
    sideLimits.push_back(side.dot(p0));
    inradius = std::min(inradius, sideLimits.back() - side.dot(centre));
  }
  // Side planes pushed out by a slop (as BoxContacts: kClipSlop times the face's half size), so
  // flush faces keep their corners, and their ids, under tiny rotations.
  const double slop = kClipSlop * inradius;
  std::vector<ClipVertex>& clipped = scratch.clipped;
  for (std::size_t k = 0; k < n; ++k) {
    const Eigen::Vector3d& side = sideNormals[k];
    // Clip ids as ManifoldBuilder's clipPolygon, on a wider field: 0x800 | plane << 4 | segment.
    clipped.clear();
    for (std::size_t v = 0; v < polygon.size(); ++v) {
      const ClipVertex& a = polygon[v];
      const ClipVertex& b = polygon[(v + 1) % polygon.size()];
      const double da = side.dot(a.position) - sideLimits[k] - slop;
      const double db = side.dot(b.position) - sideLimits[k] - slop;
      if (da <= 0.0) clipped.push_back(a);
      if ((da < 0.0 && db > 0.0) || (da > 0.0 && db < 0.0)) {
        const std::uint32_t segment = a.id & 0x800u ? 0x40u | ((a.id >> 4) & 0x3fu) : a.id & 0x3fu;
        clipped.push_back(
            {a.position + da / (da - db) * (b.position - a.position),
             0x800u | (static_cast<std::uint32_t>(k & 0x7f) << 4) | (segment & 0xfu)});
      }
    }
    std::swap(polygon, clipped);  // the storage of both stays with the scratch
    if (polygon.empty()) return;
  }
  const std::uint32_t base = (refIsB ? 1u << 31 : 0u) |
                             (static_cast<std::uint32_t>(refFace & 0xff) << 20) |
                             (static_cast<std::uint32_t>(incFace & 0xff) << 12);
  out.normal = refIsB ? Eigen::Vector3d(-refNormal) : refNormal;
  for (const ClipVertex& p : polygon) {
    const double gap = refNormal.dot(p.position) - refOffset;
    if (gap > margin) continue;
    // Back inside the reference face (undoes the slop), then midway between the two faces.
    Eigen::Vector3d q = p.position - gap * refNormal;
    for (std::size_t k = 0; k < n; ++k) {
      const double outside = sideNormals[k].dot(q) - sideLimits[k];
      if (outside > 0.0) q -= outside * sideNormals[k];
    }
    out.points.push_back({q + 0.5 * gap * refNormal, -gap, base | (p.id & 0xfffu)});
  }
}

int polytopeContact(const WorldPolytope& a, const WorldPolytope& b, double margin, PairContact& out,
                    HullScratch& scratch) {
  const auto [sepA, faceA] = faceSeparation(a, b);
  const auto [sepB, faceB] = faceSeparation(b, a);
  if (faceA < 0 || faceB < 0) return -1;
  if (std::max(sepA, sepB) > margin) return 0;
  const EdgeAxis edge = edgeSeparation(a, b);
  if (edge.separation > margin) return 0;
  const double bestFace = std::max(sepA, sepB);
  if (edge.edgeA >= 0 && edge.separation > bestFace + kEdgeTolerance) {
    const auto [a0, a1] = (*a.edges)[edge.edgeA];
    const auto [b0, b1] = (*b.edges)[edge.edgeB];
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
    faceContact(b, faceB, a, /*refIsB=*/true, margin, out, scratch);
  else
    faceContact(a, faceA, b, /*refIsB=*/false, margin, out, scratch);
  return out.points.empty() ? 0 : 1;
}

bool tooLarge(const ConvexHull& hull) {
  return hull.vertices.size() > kMaxClippedHullVertices || hull.triangles.empty();
}

}  // namespace

void buildHullFaces(ConvexHull& hull) {
  hull.faces.clear();
  double scale = 0.0;
  for (const Eigen::Vector3d& v : hull.vertices) scale = std::max(scale, v.cwiseAbs().maxCoeff());
  const double planeTolerance = 1e-9 * std::max(scale, 1e-3);
  for (const Eigen::Vector3i& t : hull.triangles) {
    const Eigen::Vector3d& a = hull.vertices[t[0]];
    const Eigen::Vector3d n = (hull.vertices[t[1]] - a).cross(hull.vertices[t[2]] - a);
    if (n.norm() <= 0.0) continue;  // degenerate triangle
    const Eigen::Vector3d normal = n.normalized();
    const double offset = normal.dot(a);
    auto same = std::find_if(hull.faces.begin(), hull.faces.end(), [&](const HullFace& f) {
      return f.normal.dot(normal) > 1.0 - 1e-10 && std::abs(f.offset - offset) < planeTolerance;
    });
    if (same == hull.faces.end()) {
      hull.faces.push_back({normal, offset, {}});
      same = std::prev(hull.faces.end());
    }
    for (int k = 0; k < 3; ++k)
      if (std::find(same->loop.begin(), same->loop.end(), t[k]) == same->loop.end())
        same->loop.push_back(t[k]);
  }
  finishFaces(hull.vertices, hull.faces, hull.edges);
}

int hullHull(const ConvexHull& a, const Pose& pa, const ConvexHull& b, const Pose& pb,
             double margin, PairContact& out, HullScratch& scratch) {
  if (tooLarge(a) || tooLarge(b)) return -1;
  hullPolytope(a, pa, scratch.facelessA, scratch.a);
  hullPolytope(b, pb, scratch.facelessB, scratch.b);
  return polytopeContact(scratch.a, scratch.b, margin, out, scratch);
}

int boxHull(const Box& a, const Pose& pa, const ConvexHull& b, const Pose& pb, double margin,
            PairContact& out, HullScratch& scratch) {
  if (tooLarge(b)) return -1;
  boxPolytope(a, pa, scratch.box, scratch.a);
  hullPolytope(b, pb, scratch.facelessB, scratch.b);
  return polytopeContact(scratch.a, scratch.b, margin, out, scratch);
}

int hullHull(const ConvexHull& a, const Pose& pa, const ConvexHull& b, const Pose& pb,
             double margin, PairContact& out) {
  HullScratch scratch;
  return hullHull(a, pa, b, pb, margin, out, scratch);
}

int boxHull(const Box& a, const Pose& pa, const ConvexHull& b, const Pose& pb, double margin,
            PairContact& out) {
  HullScratch scratch;
  return boxHull(a, pa, b, pb, margin, out, scratch);
}

}  // namespace coulomb::geometry
