#include <coulomb/geometry/HullContacts.hpp>
#include <coulomb/meshes/MakeConvexHull.hpp>
#include <coulomb/meshes/MeshLoader.hpp>
#include <coulomb/urdf/UrdfCollisions.hpp>
#include <coulomb/urdf/UrdfPaths.hpp>

#include <sstream>

namespace coulomb::engine::io {
namespace {

/// The hull of the mesh's vertices, keeping only the points on the hull (re-indexed).
geometry::ConvexHull hullOfMesh(const geometry::TriangleMesh& mesh) {
  const geometry::ConvexHull full = geometry::makeConvexHull(mesh.vertices);
  geometry::ConvexHull hull;
  std::map<int, int> remap;
  for (const Eigen::Vector3i& t : full.triangles) {
    Eigen::Vector3i mapped;
    for (int k = 0; k < 3; ++k) {
      const auto [it, inserted] = remap.emplace(t[k], static_cast<int>(hull.vertices.size()));
      if (inserted) hull.vertices.push_back(full.vertices[static_cast<std::size_t>(t[k])]);
      mapped[k] = it->second;
    }
    hull.triangles.push_back(mapped);
  }
  geometry::buildHullFaces(hull);  // the contact queries' faces and edges, re-indexed with it
  return hull;
}

}  // namespace

UrdfCollisionBuilder::UrdfCollisionBuilder(const UrdfXmlDocument& doc, std::string source,
                                           std::filesystem::path folder, const UrdfOptions& options)
    : source_(std::move(source)),
      folder_(std::move(folder)),
      options_(options),
      searchPath_(urdfSearchPath(options.packagePath, folder_)) {
  gazeboFriction_ = doc.gazebo.friction;
}

double UrdfCollisionBuilder::frictionOf(const UrdfXmlLink& link) const {
  if (const auto it = gazeboFriction_.find(link.name); it != gazeboFriction_.end())
    return it->second;
  if (const auto it = options_.materialFriction.find(link.visualMaterial);
      !link.visualMaterial.empty() && it != options_.materialFriction.end())
    return it->second;
  return options_.defaultFriction;
}

void UrdfCollisionBuilder::addLinkCollisions(const UrdfXmlLink& link,
                                             const geometry::Pose& linkInBody, UrdfBody& body) {
  for (const UrdfXmlCollision& collision : link.collisions) {
    const UrdfXmlGeometry& g = collision.geometry;
    UrdfCollision out;
    out.pose = linkInBody * collision.origin;
    out.link = link.name;
    out.material.friction = frictionOf(link);
    std::ostringstream description;
    if (g.kind == "sphere") {
      out.shape = geometry::Sphere{g.radius};
      description << "sphere r " << g.radius;
    } else if (g.kind == "box") {
      out.shape = geometry::Box{0.5 * g.size};
      description << "box " << g.size.x() << " x " << g.size.y() << " x " << g.size.z();
    } else if (g.kind == "cylinder") {
      out.shape = geometry::Cylinder{g.radius, 0.5 * g.length};
      description << "cylinder r " << g.radius << " length " << g.length;
    } else if (g.kind == "capsule") {
      // Bullet's extension: z axis, `length` between the cap centres (btCapsuleShapeZ).
      out.shape = geometry::Capsule{g.radius, 0.5 * g.length};
      description << "capsule r " << g.radius << " length " << g.length;
      if (capsuleLinks_.empty() || capsuleLinks_.back() != link.name)
        capsuleLinks_.push_back(link.name);
    } else if (g.kind == "mesh") {
      if (!options_.loadCollisionMeshes) {
        body.skippedMeshes.push_back(g.filename);
        continue;
      }
      const std::string where = source_ + ":" + std::to_string(collision.line) + ": link '" +
                                link.name + "' <collision> <mesh>";
      const std::filesystem::path path = resolveMeshPath(g.filename, searchPath_, folder_, where);
      description << "mesh " << g.filename;
      if (g.scale != Eigen::Vector3d::Ones()) description << " scale " << g.scale.transpose();
      std::ostringstream key;
      key << path.string() << '|' << g.scale.transpose();
      auto cached = meshCache_.find(key.str());
      if (cached == meshCache_.end()) {
        try {
          cached = meshCache_
                       .emplace(key.str(), std::make_shared<const geometry::ConvexHull>(hullOfMesh(
                                               geometry::loadTriangleMesh(path.string(), g.scale))))
                       .first;
        } catch (const std::exception& e) {
          throw CoulombError(where + ": " + e.what());
        }
      }
      out.shape = *cached->second;
      description << " (convex hull, " << cached->second->vertices.size() << " vertices)";
    } else {
      unknownKinds_.push_back(link.name + " <" + g.kind + ">");
      continue;
    }
    out.description = description.str();
    body.collisions.push_back(std::move(out));
  }
}

std::vector<std::string> UrdfCollisionBuilder::takeWarnings() {
  std::vector<std::string> warnings;
  auto list = [](const std::vector<std::string>& names) {
    std::string out;
    for (std::size_t i = 0; i < names.size() && i < 12; ++i) out += (i ? ", " : "") + names[i];
    if (names.size() > 12) out += ", ... (" + std::to_string(names.size()) + " in all)";
    return out;
  };
  if (!capsuleLinks_.empty())
    warnings.push_back(
        "<capsule> is Bullet's extension, not URDF; read as a z-axis capsule with `length` "
        "between the cap centres on links: " +
        list(capsuleLinks_));
  if (!unknownKinds_.empty())
    warnings.push_back("collision geometry of unknown kind skipped: " + list(unknownKinds_));
  capsuleLinks_.clear();
  unknownKinds_.clear();
  return warnings;
}

}  // namespace coulomb::engine::io
