#pragma once
//! \file input_mesh.h
//! A triangle mesh given as the surface to remesh (`delmesh mesh --input-mesh FILE`, §7 of the
//! paper, Fig. 13): read, triangulated, validated and oriented outward.  DelMesh samples a closed
//! surface Σ without boundary that bounds a volume, so the mesh must be a non-empty, closed,
//! 2-manifold, consistently oriented triangle mesh without degenerate triangles or
//! self-intersections.  Every defect is refused with InvalidInput and one line that names the
//! defect and where it is (vertex indices as in the file, 0-based, and their coordinates).
//!
//! The checks, in this order (the first failing one is reported):
//!  1. empty: no faces;
//!  2. non-manifold edge: an edge in three or more faces;
//!  3. not closed: an edge in one face only (a boundary edge);
//!  4. non-manifold vertex: a vertex whose faces form more than one fan (a pinch);
//!  5. inconsistent orientation: an edge that both of its faces traverse in the same direction
//!     (or a surface that is not orientable at all);
//!  6. degenerate triangle: three collinear vertices (exact predicate), after triangulation;
//!  7. self-intersection: two triangles that meet other than in their shared vertices or edge
//!     (PMP::self_intersections, exact predicates; the first pair found is named);
//!  8. resolution: a mesh far from the origin (largest |coordinate| ≥
//!     tolerances::input_mesh_far_ratio · diagonal) whose diagonal spans fewer than
//!     tolerances::input_mesh_min_resolution units in the last place of that coordinate.
//! Checks 2–5 are made on the faces as given, each polygon split into a fan (which adds only
//! diagonals inside the polygon, each in two of its triangles, so the edges between faces and the
//! fans around vertices are the polygons'), with the independent checker's counts and first
//! locations (mesh_checker.h); checks 6 and 7 on the final triangles.  read_input_mesh takes the
//! file's polygons as they are (read_polygon_soup, mesh_io.h).
//!
//! Faces with more than three vertices are triangulated by PMP::triangulate_faces (a constrained
//! Delaunay triangulation of each face in its best-fitting plane), which needs no convexity.
//! Points referenced by no face are dropped.  Each connected component is then oriented so that
//! the mesh bounds a volume (PMP::orient_to_bound_a_volume: outward normals on outer components,
//! inward on a cavity's boundary); the result says how many components were reversed.

#include <cstddef>
#include <string>
#include <vector>

#include "meshing/core/mesh_checker.h"
#include "meshing/core/surface_mesh.h"
#include "symbolic/surface.h"

namespace delmesh {

//! A validated input surface.
struct InputMesh {
  //! The triangles, every face outward oriented (see the file comment for nested components);
  //! vertices in the order of the file with unreferenced points removed.
  SurfaceMesh mesh;
  //! The independent checker's report on `mesh`: vertices, triangles, components,
  //! genus_per_component (sorted ascending, all ≥ 0 after validation), Euler characteristic,
  //! edge lengths, angles.
  MeshReport report;
  //! The domain box: the bounding box of the vertices, every side pushed out by
  //! tolerances::input_mesh_box_margin times the bounding box's diagonal, so Σ lies in its interior.
  Box3 box;
  double bounding_box_diagonal = 0;  //!< of the vertices (before the margin)
  double median_edge_length = 0;     //!< over the undirected edges of `mesh` (the lower median)
  std::size_t faces_read = 0;             //!< faces of the file (polygons)
  std::size_t polygons_triangulated = 0;  //!< faces of the file with more than three vertices
  std::size_t unreferenced_vertices = 0;  //!< points of the file referenced by no face (dropped)
  std::size_t components_reversed = 0;    //!< components whose orientation was reversed
  //! The folded vertices of `mesh` (meshing/inputs/folded_vertices.h): where they exist, Silhouette can
  //! never be clean and no remeshing run can end complete.
  std::vector<SurfaceMesh::Vertex_index> folded_vertices;
  bool reoriented() const { return components_reversed > 0; }
};

//! Reads `path` (OFF, PLY, OBJ or STL, by extension; meshing/inputs/mesh_io.h reads the file), then
//! validate_input_mesh.  Throws InvalidInput, with the path, for an unreadable or corrupt file
//! (mesh_io's message) or a defect of the mesh (the list in the file comment).
[[nodiscard]] InputMesh read_input_mesh(const std::string& path);

//! Triangulates, validates and orients the polygon soup (points, polygons): polygons are index
//! lists with at least three distinct indices into points.  `source` names the mesh in the
//! messages (a path).  Throws InvalidInput naming `source`, the first defect and where it is
//! (the file comment's list), or a malformed soup (an index out of range, a polygon with fewer
//! than three vertices or a repeated vertex, a non-finite coordinate).  Tests the command's limits
//! (common/run_limits.h: RunLimits::current()) between its steps and throws RunStopped once they
//! have passed (each CGAL step, such as the self-intersection test, runs to its end first).
[[nodiscard]] InputMesh validate_input_mesh(const std::vector<Point3>& points,
                                            const std::vector<std::vector<std::size_t>>& polygons,
                                            const std::string& source);

}  // namespace delmesh
