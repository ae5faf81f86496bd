#include <coulomb/meshes/MeshLoader.hpp>

#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <assimp/Importer.hpp>

#include <array>
#include <map>
#include <stdexcept>

namespace coulomb::geometry {
namespace {

Eigen::Matrix4d toEigen(const aiMatrix4x4& m) {
  Eigen::Matrix4d out;
  out << m.a1, m.a2, m.a3, m.a4, m.b1, m.b2, m.b3, m.b4, m.c1, m.c2, m.c3, m.c4, m.d1, m.d2, m.d3,
      m.d4;
  return out;
}

void collect(const aiScene& scene, const aiNode& node, const Eigen::Matrix4d& parent,
             const Eigen::Vector3d& scale, TriangleMesh& out) {
  const Eigen::Matrix4d transform = parent * toEigen(node.mTransformation);
  for (unsigned k = 0; k < node.mNumMeshes; ++k) {
    const aiMesh& mesh = *scene.mMeshes[node.mMeshes[k]];
    const int base = static_cast<int>(out.vertices.size());
    for (unsigned v = 0; v < mesh.mNumVertices; ++v) {
      const aiVector3D& p = mesh.mVertices[v];
      const Eigen::Vector4d world = transform * Eigen::Vector4d(p.x, p.y, p.z, 1.0);
      out.vertices.push_back(world.head<3>().cwiseProduct(scale));
    }
    for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
      const aiFace& face = mesh.mFaces[f];
      if (face.mNumIndices != 3) continue;  // points and lines left by aiProcess_SortByPType
      out.triangles.emplace_back(base + static_cast<int>(face.mIndices[0]),
                                 base + static_cast<int>(face.mIndices[1]),
                                 base + static_cast<int>(face.mIndices[2]));
    }
  }
  for (unsigned c = 0; c < node.mNumChildren; ++c)
    collect(scene, *node.mChildren[c], transform, scale, out);
}

// Merges vertices at the same position. assimp's JoinIdenticalVertices also compares normals, so
// an STL (one normal per facet) would stay a soup of separate triangles, which is not closed.
TriangleMesh weld(const TriangleMesh& soup) {
  TriangleMesh out;
  std::map<std::array<double, 3>, int> indexOf;
  std::vector<int> remap(soup.vertices.size());
  for (std::size_t i = 0; i < soup.vertices.size(); ++i) {
    const Eigen::Vector3d& v = soup.vertices[i];
    const auto [it, added] =
        indexOf.try_emplace({v.x(), v.y(), v.z()}, static_cast<int>(out.vertices.size()));
    if (added) out.vertices.push_back(v);
    remap[i] = it->second;
  }
  for (const Eigen::Vector3i& t : soup.triangles) {
    const Eigen::Vector3i w(remap[t[0]], remap[t[1]], remap[t[2]]);
    if (w[0] != w[1] && w[1] != w[2] && w[0] != w[2]) out.triangles.push_back(w);  // no slivers
  }
  return out;
}

}  // namespace

TriangleMesh loadTriangleMesh(const std::string& path, const Eigen::Vector3d& scale) {
  if (!scale.allFinite() || (scale.array() == 0.0).any())
    throw std::runtime_error("mesh '" + path + "': scale must be finite and non-zero");
  Assimp::Importer importer;
  const aiScene* scene = importer.ReadFile(path, aiProcess_Triangulate | aiProcess_SortByPType);
  if (!scene || !scene->mRootNode || (scene->mFlags & AI_SCENE_FLAGS_INCOMPLETE))
    throw std::runtime_error("mesh '" + path + "': cannot be read (" + importer.GetErrorString() +
                             ")");
  TriangleMesh mesh;
  collect(*scene, *scene->mRootNode, Eigen::Matrix4d::Identity(), scale, mesh);
  mesh = weld(mesh);
  if (mesh.triangles.empty()) throw std::runtime_error("mesh '" + path + "': holds no triangles");
  // A negative scale on an odd number of axes mirrors the mesh: restore outward winding.
  if (scale.prod() < 0.0)
    for (Eigen::Vector3i& t : mesh.triangles) std::swap(t[1], t[2]);
  return mesh;
}

}  // namespace coulomb::geometry
