#pragma once
// Internal to the URDF loader: <collision> elements (as read by UrdfXml, so Bullet's <capsule>
// and links urdfdom truncated are included) -> UrdfCollision shapes in their body's frame, with
// mesh paths resolved (UrdfPaths.hpp), meshes loaded as convex hulls, and friction by the policy
// of UrdfOptions.
#include <coulomb/urdf/UrdfLoader.hpp>
#include <coulomb/urdf/UrdfXml.hpp>

#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace coulomb::engine::io {

class UrdfCollisionBuilder {
 public:
  UrdfCollisionBuilder(const UrdfXmlDocument& doc, std::string source, std::filesystem::path folder,
                       const UrdfOptions& options);

  /// Appends the link's collisions to `body`, placed by `linkInBody` (the link frame in the body
  /// frame). Throws CoulombError "<file>:<line>: link 'x' <collision>: ..." for a mesh that cannot
  /// be found or read.
  void addLinkCollisions(const UrdfXmlLink& link, const geometry::Pose& linkInBody, UrdfBody& body);
  std::vector<std::string> takeWarnings();

 private:
  [[nodiscard]] double frictionOf(const UrdfXmlLink& link) const;

  std::string source_;
  std::filesystem::path folder_;
  UrdfOptions options_;
  std::vector<std::filesystem::path> searchPath_;
  std::map<std::string, double> gazeboFriction_;
  std::map<std::string, std::shared_ptr<const geometry::ConvexHull>> meshCache_;
  std::vector<std::string> capsuleLinks_, unknownKinds_;
};

}  // namespace coulomb::engine::io
