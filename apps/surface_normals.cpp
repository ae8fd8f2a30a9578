#include "apps/surface_normals.h"

#include <cmath>
#include <vector>

#include "symbolic/compiled_system.h"

namespace delmesh::app {

PointNormals surface_normals(const Surface& surface, const SurfaceMesh& mesh) {
  const std::vector<GiNaC::symbol> xyz{coordinate_x(), coordinate_y(), coordinate_z()};
  const CompiledSystem system({surface.E()}, xyz, {}, false, PolynomialFormBuild::never);
  PointNormals normals;
  normals.reserve(mesh.number_of_vertices());
  for (SurfaceMesh::Vertex_index v : mesh.vertices()) {
    const Point3& p = mesh.point(v);
    const double x[3] = {p.x(), p.y(), p.z()};
    double value = 0;
    std::array<double, 3> g{};
    system.values_and_jacobian<double>(x, nullptr, &value, g.data());
    const double length = std::hypot(g[0], g[1], g[2]);
    if (length > 0 && std::isfinite(length))
      normals.push_back({g[0] / length, g[1] / length, g[2] / length});
    else
      normals.push_back({0, 0, 0});
  }
  return normals;
}

}  // namespace delmesh::app
