// Folded vertices: the origin in the convex hull of the face normals at a vertex.  See
// folded_vertices.h.
#include "meshing/inputs/folded_vertices.h"

#include <algorithm>
#include <cmath>

#include <CGAL/Exact_predicates_exact_constructions_kernel.h>

#include "common/run_limits.h"

namespace delmesh {

namespace {

using Exact = CGAL::Exact_predicates_exact_constructions_kernel;
using ExactVector = Exact::Vector_3;

//! Whether ⟨n, d⟩ < 0 for some n of `normals` (exact).
bool some_faces_away(const std::vector<ExactVector>& normals, const ExactVector& d) {
  return std::any_of(normals.begin(), normals.end(), [&](const ExactVector& n) { return CGAL::is_negative(n * d); });
}

//! Whether the normals span ℝ³ (three of them linearly independent; exact).
bool spans_space(const std::vector<ExactVector>& normals) {
  const ExactVector zero = CGAL::NULL_VECTOR;
  for (std::size_t i = 0; i < normals.size(); ++i)
    for (std::size_t j = i + 1; j < normals.size(); ++j) {
      const ExactVector cross = CGAL::cross_product(normals[i], normals[j]);
      if (cross == zero) continue;
      for (std::size_t l = j + 1; l < normals.size(); ++l)
        if (!CGAL::is_zero(cross * normals[l])) return true;
    }
  return false;
}

//! Whether the origin is interior to the convex hull of `normals` (the test of the header).
bool origin_interior_to_hull(const std::vector<ExactVector>& normals, const Vector3& approximate_sum) {
  if (normals.size() < 4) return false;
  // A direction every face faces: not folded.
  const CGAL::Cartesian_converter<Kernel, Exact> to_exact;
  const ExactVector m = to_exact(approximate_sum);
  if (std::all_of(normals.begin(), normals.end(), [&](const ExactVector& n) { return CGAL::is_positive(n * m); }))
    return false;
  if (!spans_space(normals)) return false;
  // Every candidate extreme ray ±(n_i × n_j) of the cone C must leave C.
  const ExactVector zero = CGAL::NULL_VECTOR;
  for (std::size_t i = 0; i < normals.size(); ++i)
    for (std::size_t j = i + 1; j < normals.size(); ++j) {
      const ExactVector ray = CGAL::cross_product(normals[i], normals[j]);
      if (ray == zero) continue;
      if (!some_faces_away(normals, ray) || !some_faces_away(normals, -ray)) return false;
    }
  return true;
}

}  // namespace

std::vector<SurfaceMesh::Vertex_index> folded_vertices(const SurfaceMesh& mesh) {
  const CGAL::Cartesian_converter<Kernel, Exact> to_exact;
  // Each face's normal once, by face index, exactly; and its direction in doubles (any
  // approximation: it only proposes the direction m of the header's first test).
  const std::size_t face_slots = mesh.number_of_faces() + mesh.number_of_removed_faces();
  std::vector<ExactVector> face_normal(face_slots);
  std::vector<Vector3> approximate_unit(face_slots, CGAL::NULL_VECTOR);
  for (const auto f : mesh.faces()) {
    const auto h = mesh.halfedge(f);
    const Point3 &pa = mesh.point(mesh.source(h)), &pb = mesh.point(mesh.target(h)),
                 &pc = mesh.point(mesh.target(mesh.next(h)));
    face_normal[f] = CGAL::cross_product(to_exact(pb) - to_exact(pa), to_exact(pc) - to_exact(pa));
    const Vector3 n = CGAL::cross_product(pb - pa, pc - pa);
    const double length = std::sqrt(n.squared_length());
    if (std::isfinite(length) && length > 0) approximate_unit[f] = n / length;
  }
  const RunLimits& limits = RunLimits::current();
  std::vector<SurfaceMesh::Vertex_index> folded;
  std::vector<ExactVector> normals;
  for (const auto v : mesh.vertices()) {
    if (mesh.is_isolated(v)) continue;
    limits.check("finding folded vertices");
    normals.clear();
    Vector3 sum = CGAL::NULL_VECTOR;
    for (const auto f : CGAL::faces_around_target(mesh.halfedge(v), mesh))
      if (f != SurfaceMesh::null_face()) {
        normals.push_back(face_normal[f]);
        sum = sum + approximate_unit[f];
      }
    if (origin_interior_to_hull(normals, sum)) folded.push_back(v);
  }
  return folded;
}

}  // namespace delmesh
