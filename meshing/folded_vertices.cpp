// Folded vertices: the origin in the convex hull of the face normals at a vertex.  See
// folded_vertices.h.
#include "meshing/folded_vertices.h"

#include <CGAL/Exact_predicates_exact_constructions_kernel.h>

namespace delmesh {

namespace {

using Exact = CGAL::Exact_predicates_exact_constructions_kernel;

// Whether the origin lies in the interior of the tetrahedron abcd, which must not be flat
// (orientation s): replacing any one corner by the origin keeps the orientation.
bool tetrahedron_holds_origin(const Exact::Point_3& a, const Exact::Point_3& b, const Exact::Point_3& c,
                              const Exact::Point_3& d, CGAL::Orientation s) {
  const Exact::Point_3 o = CGAL::ORIGIN;
  return CGAL::orientation(o, b, c, d) == s && CGAL::orientation(a, o, c, d) == s &&
         CGAL::orientation(a, b, o, d) == s && CGAL::orientation(a, b, c, o) == s;
}

// Whether the origin is interior to a tetrahedron spanned by four of the normals.
bool origin_in_hull(const std::vector<Exact::Point_3>& normals) {
  const std::size_t k = normals.size();
  for (std::size_t i = 0; i < k; ++i)
    for (std::size_t j = i + 1; j < k; ++j)
      for (std::size_t l = j + 1; l < k; ++l)
        for (std::size_t m = l + 1; m < k; ++m) {
          const auto s = CGAL::orientation(normals[i], normals[j], normals[l], normals[m]);
          if (s != CGAL::COPLANAR && tetrahedron_holds_origin(normals[i], normals[j], normals[l], normals[m], s))
            return true;
        }
  return false;
}

}  // namespace

std::vector<SurfaceMesh::Vertex_index> folded_vertices(const SurfaceMesh& mesh) {
  // Each face's normal once, by face index.
  const CGAL::Cartesian_converter<Kernel, Exact> to_exact;
  std::vector<Exact::Point_3> face_normal(mesh.number_of_faces() + mesh.number_of_removed_faces());
  for (const auto f : mesh.faces()) {
    const auto h = mesh.halfedge(f);
    const Exact::Point_3 a = to_exact(mesh.point(mesh.source(h)));
    const Exact::Point_3 b = to_exact(mesh.point(mesh.target(h)));
    const Exact::Point_3 c = to_exact(mesh.point(mesh.target(mesh.next(h))));
    face_normal[f] = CGAL::ORIGIN + CGAL::cross_product(b - a, c - a);
  }
  std::vector<SurfaceMesh::Vertex_index> folded;
  std::vector<Exact::Point_3> normals;
  for (const auto v : mesh.vertices()) {
    if (mesh.is_isolated(v)) continue;
    normals.clear();
    for (const auto f : CGAL::faces_around_target(mesh.halfedge(v), mesh))
      if (f != SurfaceMesh::null_face()) normals.push_back(face_normal[f]);
    if (normals.size() >= 4 && origin_in_hull(normals)) folded.push_back(v);
  }
  return folded;
}

}  // namespace delmesh
