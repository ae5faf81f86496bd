#include <coulomb/geometry/BoxContacts.hpp>

#include <coulomb/geometry/PrimitiveContacts.hpp>

#include <algorithm>
#include <cmath>

namespace coulomb::geometry {
namespace {

// Prefer a face of `a` over a face of `b`, and faces over edges, unless the other is clearly
// better: keeps the chosen features (and so the feature ids) fixed under tiny motions
// (same idea as Box2D's b2CollidePolygons tolerances).
constexpr double kFaceTolerance = 1e-5;
constexpr double kEdgeTolerance = 1e-4;
// An edge-edge axis must also beat the best face axis by this fraction of the smallest half
// extent of the two boxes. Two boxes stacked face on face with a small relative tilt and yaw have
// edge-cross axes within a few degrees of the face normal whose separation exceeds the face's by
// 1e-4 to 1e-3 m (0.2 m boxes of the 1000-box pile, docs/scene-specifications.md B1): with the
// absolute 1e-4 m alone such a stack got a one-point edge manifold, the upper box pivoted about it
// and sank into the lower one (box 247 into box 147: 2.8 cm at step 27, 10 cm at step 39; 0.23 m
// overlaps by step 83). Within the tolerance the face is clipped (up to 4 points); its separation
// differs from the edge axis's by less than the tolerance.
constexpr double kEdgeRelativeTolerance = 0.025;
constexpr double kClipSlop = 2e-3;  // relative to the reference face's smaller half-extent

struct BoxFrame {
  Eigen::Vector3d centre;
  Eigen::Matrix3d axes;  // columns are the box axes in world
  Eigen::Vector3d half;
};

// Clips the incident face of `inc` against face (axis, sign) of `ref`; normal nRef points from
// ref toward inc.
void faceContact(const BoxFrame& ref, int axis, double sign, const BoxFrame& inc, bool refIsB,
                 double margin, PairContact& out) {
  const Eigen::Vector3d nRef = sign * ref.axes.col(axis);
  const Eigen::Vector3d alignment = inc.axes.transpose() * nRef;
  int j = 0;
  alignment.cwiseAbs().maxCoeff(&j);
  const double incSign = alignment[j] > 0.0 ? -1.0 : 1.0;  // incident face looks back at ref
  const Eigen::Vector3d incCentre = inc.centre + incSign * inc.half[j] * inc.axes.col(j);
  const int k1 = (j + 1) % 3, k2 = (j + 2) % 3;
  const Eigen::Vector3d e1 = inc.half[k1] * inc.axes.col(k1), e2 = inc.half[k2] * inc.axes.col(k2);
  ClipPolygon polygon;
  polygon.vertices[0] = {incCentre + e1 + e2, 0u};
  polygon.vertices[1] = {incCentre - e1 + e2, 1u};
  polygon.vertices[2] = {incCentre - e1 - e2, 2u};
  polygon.vertices[3] = {incCentre + e1 - e2, 3u};
  polygon.count = 4;
  const Eigen::Vector3d refCentre = ref.centre + ref.half[axis] * nRef;
  const int u = (axis + 1) % 3, v = (axis + 2) % 3;
  const Eigen::Vector3d du = ref.axes.col(u), dv = ref.axes.col(v);
  // Side planes pushed out by a slop: equal boxes stacked flush have their incident corners
  // exactly on the reference edges, and without it each tiny rotation would swap 4 corners for
  // 8 clipped points with new ids, losing the warm start.
  const double slop = kClipSlop * std::min(ref.half[u], ref.half[v]);
  clipPolygon(polygon, du, du.dot(refCentre) + ref.half[u] + slop, 0);
  clipPolygon(polygon, -du, -du.dot(refCentre) + ref.half[u] + slop, 1);
  clipPolygon(polygon, dv, dv.dot(refCentre) + ref.half[v] + slop, 2);
  clipPolygon(polygon, -dv, -dv.dot(refCentre) + ref.half[v] + slop, 3);

  const std::uint32_t refFace = static_cast<std::uint32_t>(2 * axis + (sign < 0.0 ? 1 : 0));
  const std::uint32_t incFace = static_cast<std::uint32_t>(2 * j + (incSign < 0.0 ? 1 : 0));
  const std::uint32_t base = (refIsB ? 1u << 31 : 0u) | (refFace << 20) | (incFace << 12);
  out.normal = refIsB ? Eigen::Vector3d(-nRef) : nRef;
  for (const ClipVertex& p : polygon) {
    const double gap = nRef.dot(p.position - refCentre);
    if (gap > margin) continue;
    // Back onto the reference face (undoes the slop), then midway between the two faces.
    const Eigen::Vector3d r = p.position - refCentre;
    const double cu = std::clamp(du.dot(r), -ref.half[u], ref.half[u]);
    const double cv = std::clamp(dv.dot(r), -ref.half[v], ref.half[v]);
    out.points.push_back({refCentre + cu * du + cv * dv + 0.5 * gap * nRef, -gap, base | p.id});
  }
}

}  // namespace

bool boxBox(const Box& a, const Pose& pa, const Box& b, const Pose& pb, double margin,
            PairContact& out) {
  const BoxFrame A{pa.position, pa.rotationMatrix(), a.halfExtents};
  const BoxFrame B{pb.position, pb.rotationMatrix(), b.halfExtents};
  const Eigen::Vector3d d = B.centre - A.centre;

  // Separation along every candidate axis (> 0: a gap of that size along the axis), in A's frame
  // (Gottschalk, Lin and Manocha, OBBTree, SIGGRAPH 1996, sec. 4): with C = A^T B (C_ij = A_i .
  // B_j) and t = A^T d, the 15 axes need no world-frame products. Edge axis A_i x B_j has length L
  // = |C_{i+1,j}, C_{i+2,j}|; its projection of d is t_{i+2} C_{i+1,j} - t_{i+1} C_{i+2,j}, A's
  // radius along it a_{i+1} |C_{i+2,j}| + a_{i+2} |C_{i+1,j}|, B's b_{j+1} |C_{i,j+2}| +
  // b_{j+2} |C_{i,j+1}| (all over L).
  const Eigen::Matrix3d C = A.axes.transpose() * B.axes;
  const Eigen::Matrix3d absC = C.cwiseAbs();
  const Eigen::Vector3d t = A.axes.transpose() * d;
  const Eigen::Vector3d &ha = A.half, &hb = B.half;
  double bestA = -1e300, bestB = -1e300, bestEdge = -1e300;
  int faceA = 0, faceB = 0, edgeI = -1, edgeJ = -1;
  for (int i = 0; i < 3; ++i) {
    const double sep = std::abs(t[i]) - ha[i] - absC.row(i).dot(hb);
    if (sep > bestA) bestA = sep, faceA = i;
  }
  for (int j = 0; j < 3; ++j) {
    const double sep = std::abs(C.col(j).dot(t)) - hb[j] - absC.col(j).dot(ha);
    if (sep > bestB) bestB = sep, faceB = j;
  }
  for (int i = 0; i < 3; ++i) {
    const int i1 = (i + 1) % 3, i2 = (i + 2) % 3;
    for (int j = 0; j < 3; ++j) {
      const int j1 = (j + 1) % 3, j2 = (j + 2) % 3;
      const double length = std::sqrt(C(i1, j) * C(i1, j) + C(i2, j) * C(i2, j));
      if (length < 1e-6) continue;  // parallel edges: covered by the face axes
      const double sep = (std::abs(t[i2] * C(i1, j) - t[i1] * C(i2, j)) -
                          (ha[i1] * absC(i2, j) + ha[i2] * absC(i1, j)) -
                          (hb[j1] * absC(i, j2) + hb[j2] * absC(i, j1))) /
                         length;
      if (sep > bestEdge) bestEdge = sep, edgeI = i, edgeJ = j;
    }
  }
  if (std::max({bestA, bestB, bestEdge}) > margin) return false;  // separated beyond the margin

  const double bestFace = std::max(bestA, bestB);
  const double edgeTolerance = std::max(
      kEdgeTolerance, kEdgeRelativeTolerance * std::min(A.half.minCoeff(), B.half.minCoeff()));
  if (edgeI >= 0 && bestEdge > bestFace + edgeTolerance) {
    Eigen::Vector3d axis = A.axes.col(edgeI).cross(B.axes.col(edgeJ)).normalized();
    if (axis.dot(d) < 0.0) axis = -axis;
    Eigen::Vector3d onA = A.centre, onB = B.centre;
    for (int k = 0; k < 3; ++k) {
      if (k != edgeI) onA += A.half[k] * (axis.dot(A.axes.col(k)) > 0 ? 1.0 : -1.0) * A.axes.col(k);
      if (k != edgeJ) onB -= B.half[k] * (axis.dot(B.axes.col(k)) > 0 ? 1.0 : -1.0) * B.axes.col(k);
    }
    const Eigen::Vector3d ea = A.half[edgeI] * A.axes.col(edgeI);
    const Eigen::Vector3d eb = B.half[edgeJ] * B.axes.col(edgeJ);
    Eigen::Vector3d ca, cb;
    closestSegmentPoints(onA - ea, onA + ea, onB - eb, onB + eb, ca, cb);
    const double gap = axis.dot(cb - ca);
    out.normal = axis;
    out.points.push_back({0.5 * (ca + cb), -gap,
                          (1u << 30) | (static_cast<std::uint32_t>(edgeI) << 4) |
                              static_cast<std::uint32_t>(edgeJ)});
    return gap <= margin;
  }
  if (bestB > bestA + kFaceTolerance) {
    const double sign = B.axes.col(faceB).dot(-d) >= 0.0 ? 1.0 : -1.0;
    faceContact(B, faceB, sign, A, /*refIsB=*/true, margin, out);
  } else {
    const double sign = A.axes.col(faceA).dot(d) >= 0.0 ? 1.0 : -1.0;
    faceContact(A, faceA, sign, B, /*refIsB=*/false, margin, out);
  }
  return !out.points.empty();
}

BoxCapsuleResult boxCapsule(const Box& a, const Pose& pa, const Capsule& b, const Pose& pb,
                            double margin, PairContact& out) {
  const Eigen::Vector3d& h = a.halfExtents;
  // Capsule axis in the box frame.
  const Eigen::Vector3d p0 = pa.applyInverse(pb.apply(Eigen::Vector3d(0, 0, -b.halfLength)));
  const Eigen::Vector3d p1 = pa.applyInverse(pb.apply(Eigen::Vector3d(0, 0, b.halfLength)));
  const Eigen::Vector3d dir = p1 - p0;
  auto distanceSq = [&](double t) {
    const Eigen::Vector3d q = p0 + t * dir;
    return (q - q.cwiseMax(-h).cwiseMin(h)).squaredNorm();
  };
  // The distance from a point moving on a segment to a convex set is convex in t: golden-section
  // search finds its minimum (Press et al., Numerical Recipes 3rd ed., 10.2).
  const double ratio = (std::sqrt(5.0) - 1.0) / 2.0;
  double lo = 0.0, hi = 1.0;
  double x1 = hi - ratio * (hi - lo), x2 = lo + ratio * (hi - lo);
  double f1 = distanceSq(x1), f2 = distanceSq(x2);
  for (int iteration = 0; iteration < 80 && hi - lo > 1e-13; ++iteration) {
    if (f1 <= f2) {
      hi = x2, x2 = x1, f2 = f1;
      x1 = hi - ratio * (hi - lo), f1 = distanceSq(x1);
    } else {
      lo = x1, x1 = x2, f1 = f2;
      x2 = lo + ratio * (hi - lo), f2 = distanceSq(x2);
    }
  }
  double t = 0.5 * (lo + hi);
  for (double end : {0.0, 1.0})  // the search interval is open: check the ends too
    if (distanceSq(end) < distanceSq(t)) t = end;
  const Eigen::Vector3d q = p0 + t * dir;
  const Eigen::Vector3d onBox = q.cwiseMax(-h).cwiseMin(h);
  const double dist = (q - onBox).norm();
  if (dist - b.radius > margin) return BoxCapsuleResult::Separated;
  if (dist < 1e-9) return BoxCapsuleResult::AxisInsideBox;
  const Eigen::Vector3d n = (q - onBox) / dist;  // box -> capsule, box frame

  int face = 0;
  n.cwiseAbs().maxCoeff(&face);
  if (std::abs(n[face]) >= 1.0 - 1e-9) {  // closest feature is a face: clip the segment to it
    const double s = n[face] > 0.0 ? 1.0 : -1.0;
    double tlo = 0.0, thi = 1.0;
    for (int k = 0; k < 3; ++k) {  // Liang-Barsky against the face's side slabs
      if (k == face) continue;
      if (std::abs(dir[k]) < 1e-15) continue;
      double ta = (-h[k] - p0[k]) / dir[k], tb = (h[k] - p0[k]) / dir[k];
      if (ta > tb) std::swap(ta, tb);
      tlo = std::max(tlo, ta), thi = std::min(thi, tb);
    }
    if (tlo <= thi) {
      out.normal = pa.rotation * (s * Eigen::Vector3d::Unit(face));
      const int count = (thi - tlo) * dir.norm() > 1e-12 ? 2 : 1;
      for (int k = 0; k < count; ++k) {
        const Eigen::Vector3d qk = p0 + (k ? thi : tlo) * dir;
        const double gap = s * qk[face] - h[face] - b.radius;
        if (gap > margin) continue;
        Eigen::Vector3d local = qk;
        local[face] = s * (h[face] + 0.5 * gap);  // midway between the face and the capsule
        out.points.push_back({pa.apply(local), -gap, static_cast<std::uint32_t>(k)});
      }
      return out.points.empty() ? BoxCapsuleResult::Separated : BoxCapsuleResult::Touching;
    }
  }
  const double gap = dist - b.radius;
  out.normal = pa.rotation * n;
  out.points.push_back({pa.apply(onBox + 0.5 * (dist - b.radius) * n), -gap, 2});
  return BoxCapsuleResult::Touching;
}

}  // namespace coulomb::geometry
