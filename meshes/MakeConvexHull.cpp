#include <coulomb/meshes/MakeConvexHull.hpp>

#include <coulomb/geometry/HullContacts.hpp>

#include <Eigen/Geometry>

#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <string>

extern "C" {
#include <libqhull_r/qhull_ra.h>
}

namespace coulomb::geometry {
namespace {

// Qhull reports errors on a FILE*; capture them in memory so the message can be returned.
class MemoryStream {
 public:
  MemoryStream() : file_(open_memstream(&buffer_, &size_)) {}
  ~MemoryStream() {
    if (file_ != nullptr) std::fclose(file_);
    std::free(buffer_);
  }
  MemoryStream(const MemoryStream&) = delete;
  MemoryStream& operator=(const MemoryStream&) = delete;
  FILE* file() const { return file_; }
  std::string text() {
    if (file_ != nullptr) std::fflush(file_);
    return buffer_ != nullptr ? std::string(buffer_, size_) : std::string();
  }

 private:
  char* buffer_ = nullptr;
  std::size_t size_ = 0;
  FILE* file_ = nullptr;
};

std::string firstLine(const std::string& text) {
  const auto start = text.find_first_not_of(" \n");
  if (start == std::string::npos) return "qhull failed";
  return text.substr(start, text.find('\n', start) - start);
}

}  // namespace

ConvexHull makeConvexHull(const std::vector<Eigen::Vector3d>& points) {
  if (points.size() < 4)
    throw std::invalid_argument("convex_hull needs at least 4 points (got " +
                                std::to_string(points.size()) + ")");
  std::vector<coordT> coordinates;
  coordinates.reserve(3 * points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (!points[i].allFinite())
      throw std::invalid_argument("convex_hull point " + std::to_string(i) + " is not finite");
    coordinates.insert(coordinates.end(), {points[i].x(), points[i].y(), points[i].z()});
  }

  MemoryStream errors;
  qhT qhullState;
  qhT* qh = &qhullState;
  qh_zero(qh, errors.file());
  char options[] = "qhull Qt";  // triangulated output
  const int status = qh_new_qhull(qh, 3, static_cast<int>(points.size()), coordinates.data(), False,
                                  options, nullptr, errors.file());
  ConvexHull hull;
  hull.vertices = points;
  if (status == 0) {
    Eigen::Vector3d interior = Eigen::Vector3d::Zero();
    int hullVertices = 0;
    for (vertexT* vertex = qh->vertex_list; vertex && vertex->next; vertex = vertex->next) {
      interior += points[static_cast<std::size_t>(qh_pointid(qh, vertex->point))];
      ++hullVertices;
    }
    interior /= std::max(hullVertices, 1);
    for (facetT* facet = qh->facet_list; facet && facet->next; facet = facet->next) {
      Eigen::Vector3i tri;
      int corner = 0;
      for (int k = 0; k < qh_setsize(qh, facet->vertices) && corner < 3; ++k) {
        auto* vertex = static_cast<vertexT*>(SETelem_(facet->vertices, k));
        tri[corner++] = qh_pointid(qh, vertex->point);
      }
      if (corner != 3) continue;
      const Eigen::Vector3d a = points[tri[0]], b = points[tri[1]], c = points[tri[2]];
      const Eigen::Vector3d normal = (b - a).cross(c - a);
      if (normal.squaredNorm() == 0.0) continue;  // degenerate sliver from triangulation
      if (normal.dot((a + b + c) / 3.0 - interior) < 0.0) std::swap(tri[1], tri[2]);
      hull.triangles.push_back(tri);
    }
  }
  const std::string message = errors.text();
  qh_freeqhull(qh, !qh_ALL);
  int currentLong = 0, totalLong = 0;
  qh_memfreeshort(qh, &currentLong, &totalLong);
  if (status != 0 || hull.triangles.size() < 4)
    throw std::invalid_argument("convex_hull points are degenerate (coplanar or collinear): " +
                                firstLine(message));
  buildHullFaces(hull);
  return hull;
}

}  // namespace coulomb::geometry
