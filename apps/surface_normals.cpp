#include "apps/surface_normals.h"

#include <cmath>
#include <limits>

namespace delmesh::app {

PointNormals surface_normals(const ImplicitOracle& oracle, const SurfaceMesh& mesh) {
  PointNormals normals;
  normals.reserve(mesh.number_of_vertices());
  for (SurfaceMesh::Vertex_index v : mesh.vertices()) {
    const Point3& p = mesh.point(v);
    const Vec3 g = oracle.gradient(Vec3{p.x(), p.y(), p.z()});
    const double length = std::hypot(g[0], g[1], g[2]);
    if (length > 0 && std::isfinite(length))
      normals.push_back({g[0] / length, g[1] / length, g[2] / length});
    else
      normals.push_back({0, 0, 0});
  }
  return normals;
}

PointDistances vertex_distance_bounds(const SurfaceMesh& mesh, const std::vector<double>& triangle_bounds) {
  if (triangle_bounds.empty() || triangle_bounds.size() != mesh.number_of_faces()) return {};
  const std::size_t slots = mesh.number_of_vertices() + mesh.number_of_removed_vertices();
  std::vector<double> least(slots, std::numeric_limits<double>::infinity());
  std::size_t face = 0;
  for (SurfaceMesh::Face_index f : mesh.faces()) {
    const double bound = triangle_bounds[face++];
    if (!(std::isfinite(bound) && bound >= 0)) return {};
    for (SurfaceMesh::Vertex_index v : CGAL::vertices_around_face(mesh.halfedge(f), mesh)) {
      double& d = least[static_cast<std::size_t>(v)];
      d = std::min(d, bound);
    }
  }
  PointDistances out;
  out.reserve(mesh.number_of_vertices());
  for (SurfaceMesh::Vertex_index v : mesh.vertices()) {
    const double d = least[static_cast<std::size_t>(v)];
    if (!std::isfinite(d)) return {};  // a vertex on no face: it has no bound
    out.push_back(d);
  }
  return out;
}

}  // namespace delmesh::app
