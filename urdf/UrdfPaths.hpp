#pragma once
// Internal to the URDF loader: where a <mesh filename> lives (docs/urdf.md, "Search path").
#include <filesystem>
#include <string>
#include <vector>

namespace coulomb::engine::io {

/// The folders searched, in order: `options` (UrdfOptions::packagePath), then every entry of the
/// environment variable COULOMB_PACKAGE_PATH (':'-separated), then the URDF's folder and its
/// ancestors (up to three levels: a ROS package keeps its URDF in <package>/urdf/).
std::vector<std::filesystem::path> urdfSearchPath(const std::vector<std::filesystem::path>& options,
                                                  const std::filesystem::path& urdfFolder);

/// Resolves `package://<package>/<rest>` (also `package:///...`), `file://<absolute>`, absolute
/// paths and paths relative to the URDF's folder. For package URIs each search folder D is tried
/// as D/<package>/<rest>, D/<rest>, and D itself when it is named <package>. Throws CoulombError
/// listing the candidates tried (and how to extend the search path) when none exists.
std::filesystem::path resolveMeshPath(const std::string& uri,
                                      const std::vector<std::filesystem::path>& searchPath,
                                      const std::filesystem::path& urdfFolder,
                                      const std::string& where);

}  // namespace coulomb::engine::io
