#include <coulomb/engine/CoulombError.hpp>
#include <coulomb/urdf/UrdfPaths.hpp>

#include <cstdlib>
#include <sstream>

namespace coulomb::engine::io {

namespace fs = std::filesystem;

std::vector<fs::path> urdfSearchPath(const std::vector<fs::path>& options,
                                     const fs::path& urdfFolder) {
  std::vector<fs::path> folders(options.begin(), options.end());
  if (const char* env = std::getenv("COULOMB_PACKAGE_PATH")) {
    std::stringstream entries(env);
    for (std::string entry; std::getline(entries, entry, ':');)
      if (!entry.empty()) folders.emplace_back(entry);
  }
  fs::path folder = urdfFolder.empty() ? fs::path(".") : urdfFolder;
  for (int level = 0; level < 4; ++level) {
    folders.push_back(folder);
    const fs::path parent = fs::absolute(folder).lexically_normal().parent_path();
    if (parent == fs::absolute(folder).lexically_normal() || parent.empty()) break;
    folder = parent;
  }
  return folders;
}

fs::path resolveMeshPath(const std::string& uri, const std::vector<fs::path>& searchPath,
                         const fs::path& urdfFolder, const std::string& where) {
  std::vector<fs::path> candidates;
  const std::string packagePrefix = "package://", filePrefix = "file://";
  if (uri.rfind(packagePrefix, 0) == 0) {
    std::string rest = uri.substr(packagePrefix.size());
    while (!rest.empty() && rest.front() == '/') rest.erase(0, 1);  // package:///name/...
    const std::size_t slash = rest.find('/');
    const std::string package = rest.substr(0, slash);
    const std::string inside = slash == std::string::npos ? "" : rest.substr(slash + 1);
    for (const fs::path& folder : searchPath) {
      candidates.push_back(folder / package / inside);
      candidates.push_back(folder / inside);
      if (fs::absolute(folder).lexically_normal().filename() == package)
        candidates.push_back(folder / inside);
    }
  } else if (uri.rfind(filePrefix, 0) == 0) {
    candidates.emplace_back(uri.substr(filePrefix.size()));
  } else if (fs::path(uri).is_absolute()) {
    candidates.emplace_back(uri);
  } else {
    candidates.push_back((urdfFolder.empty() ? fs::path(".") : urdfFolder) / uri);
    for (const fs::path& folder : searchPath) candidates.push_back(folder / uri);
  }
  for (const fs::path& candidate : candidates) {
    std::error_code error;
    if (fs::is_regular_file(candidate, error)) return candidate.lexically_normal();
  }
  std::ostringstream out;
  out << where << ": mesh '" << uri << "' not found; tried";
  for (std::size_t i = 0; i < candidates.size() && i < 8; ++i)
    out << (i == 0 ? " " : ", ") << candidates[i].lexically_normal().string();
  if (candidates.size() > 8) out << " and " << candidates.size() - 8 << " more";
  out << ". Add the folder that stands for the package to the search path (--package-path, "
         "UrdfOptions::packagePath or COULOMB_PACKAGE_PATH=dir1:dir2), or load without meshes";
  throw CoulombError(out.str());
}

}  // namespace coulomb::engine::io
