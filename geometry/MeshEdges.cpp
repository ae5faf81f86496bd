#include <coulomb/geometry/MeshEdges.hpp>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <tuple>

namespace coulomb::geometry {

namespace {

// Union-find root with path halving; roots are the lowest index of their set.
std::uint32_t root(std::vector<std::uint32_t>& parent, std::uint32_t t) {
  while (parent[t] != t) t = parent[t] = parent[parent[t]];
  return t;
}

}  // namespace

MeshSurface meshSurface(const TriangleMesh& mesh) {
  const std::size_t count = mesh.triangles.size();
  MeshSurface surface;
  std::vector<std::uint8_t>& flags = surface.activeEdges;
  flags.assign(count, 0x7);
  std::vector<std::uint32_t>& patch = surface.patch;
  patch.resize(count);
  for (std::size_t t = 0; t < count; ++t) patch[t] = static_cast<std::uint32_t>(t);
  // Every edge once per triangle, keyed by its sorted vertex pair; equal keys are neighbours.
  std::vector<std::tuple<int, int, int, int>> edges;  // (low, high, triangle, edge)
  edges.reserve(3 * count);
  for (std::size_t t = 0; t < count; ++t)
    for (int k = 0; k < 3; ++k) {
      const int i = mesh.triangles[t][k], j = mesh.triangles[t][(k + 1) % 3];
      edges.emplace_back(std::min(i, j), std::max(i, j), static_cast<int>(t), k);
    }
  std::sort(edges.begin(), edges.end());
  auto normalOf = [&](int t) {
    const Eigen::Vector3i& tri = mesh.triangles[static_cast<std::size_t>(t)];
    const Eigen::Vector3d& a = mesh.vertices[static_cast<std::size_t>(tri[0])];
    return Eigen::Vector3d((mesh.vertices[static_cast<std::size_t>(tri[1])] - a)
                               .cross(mesh.vertices[static_cast<std::size_t>(tri[2])] - a)
                               .normalized());
  };
  const double flatCos = std::cos(kActiveEdgeAngle);
  for (std::size_t e = 0; e < edges.size();) {
    std::size_t end = e + 1;
    while (end < edges.size() && std::get<0>(edges[end]) == std::get<0>(edges[e]) &&
           std::get<1>(edges[end]) == std::get<1>(edges[e]))
      ++end;
    if (end - e == 2) {  // a manifold edge: internal unless a convex crease
      const auto [low, high, t, k] = edges[e];
      const auto [low2, high2, u, l] = edges[e + 1];
      const Eigen::Vector3d nt = normalOf(t), nu = normalOf(u);
      // u's vertex off the edge, seen from t's plane: below it (convex) or on/above (concave).
      const Eigen::Vector3i& triU = mesh.triangles[static_cast<std::size_t>(u)];
      const Eigen::Vector3d& apex = mesh.vertices[static_cast<std::size_t>(triU[(l + 2) % 3])];
      const Eigen::Vector3d& onEdge = mesh.vertices[static_cast<std::size_t>(low)];
      const bool convex = nt.dot(apex - onEdge) < 0.0;
      const bool active = convex && nt.dot(nu) < flatCos;
      if (!active) {
        flags[static_cast<std::size_t>(t)] &= static_cast<std::uint8_t>(~(1u << k));
        flags[static_cast<std::size_t>(u)] &= static_cast<std::uint8_t>(~(1u << l));
        const std::uint32_t rt = root(patch, static_cast<std::uint32_t>(t));
        const std::uint32_t ru = root(patch, static_cast<std::uint32_t>(u));
        patch[std::max(rt, ru)] = std::min(rt, ru);
      }
      (void)high;
      (void)low2;
      (void)high2;
    }
    e = end;
  }
  for (std::size_t t = 0; t < count; ++t) patch[t] = root(patch, static_cast<std::uint32_t>(t));
  return surface;
}

}  // namespace coulomb::geometry
