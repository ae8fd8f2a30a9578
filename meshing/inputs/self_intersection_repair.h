#pragma once
//! \file self_intersection_repair.h
//! `delmesh mesh --input-mesh FILE --repair`: a closed mesh that intersects itself is repaired by
//! CGAL's self-intersection removal and then validated as any input mesh is
//! (meshing/inputs/input_mesh.h); a mesh that cannot be repaired into a valid one is refused.
//!
//! The steps, on the polygon soup of the file:
//!  1. The soup must be a closed, manifold, consistently oriented polygon mesh already (checks 1–5
//!     and 6 of input_mesh.h, with their messages): repair removes intersections, it does not
//!     close holes or mend non-manifold edges.  Polygons are triangulated as read_input_mesh
//!     does it; each component is oriented outward (PMP::orient).
//!  2. No pair of triangles intersects (PMP::does_self_intersect, exact predicates): nothing is
//!     changed; the result is validate_input_mesh of the soup as read, method "none".
//!  3. Otherwise PMP::experimental::autorefine_and_remove_self_intersections (CGAL 5.5): the mesh
//!     is refined along its self-intersection curves (intersection points constructed exactly
//!     and rounded to double), the patches that end up inside the volume (extra sheets) are
//!     removed and the rest is stitched along the intersection curves, so the surface kept is the
//!     boundary of the union of what the mesh encloses; no vertex of the kept surface moves, new
//!     vertices lie on the intersection curves.  Method "autorefine" when CGAL reports every
//!     self-intersection fixed, the result is a closed mesh, has no more connected components
//!     than the input and keeps at least half of its area (the surface kept is part of the
//!     input's, so losing most of it means the inside/outside classification failed: on CGAL's
//!     cow.off it keeps 10 of 5804 triangles).
//!  4. Else PMP::experimental::remove_self_intersections on the oriented mesh of step 1 (local:
//!     the intersecting faces and their neighbourhoods are smoothed or removed and the holes
//!     refilled, with genus preserved, up to 7 growing rounds): method "local".  It moves and
//!     replaces faces near the intersections, so the surface changes there.
//! Steps 3 and 4 each run in a forked child process that sends its mesh back through a pipe
//! (the experimental code can crash: autorefinement dies with SIGSEGV on CGAL's diplodocus.off);
//! a child that dies is a failed attempt, named in the refusal.
//!  5. The result, as a triangle soup, goes through validate_input_mesh: it must be closed,
//!     manifold, without degenerate triangles and without self-intersections (rounding the
//!     constructed points can create new ones).
//! Refusal (InvalidInput, one line): "input mesh 'F': --repair could not remove the
//! self-intersections: …" with what failed last (CGAL's verdict, the defect validation found).

#include <cstddef>
#include <string>
#include <vector>

#include "meshing/inputs/input_mesh.h"

namespace delmesh {

//! What repair_input_mesh did.
struct RepairReport {
  std::string method = "none";            //!< "none", "autorefine" or "local" (file comment)
  std::size_t intersecting_pairs = 0;     //!< pairs of triangles of the input that intersect
  std::size_t faces_before = 0;           //!< triangles after triangulating the file's faces
  std::size_t faces_after = 0;            //!< triangles of the repaired mesh
  std::size_t vertices_before = 0;        //!< referenced vertices of the file
  std::size_t vertices_after = 0;         //!< vertices of the repaired mesh
  double seconds = 0;                     //!< wall-clock time of the steps above
  bool changed() const { return method != "none"; }
  //! One line: what was found and done, e.g. "bones.off: 12 pairs of intersecting triangles
  //! removed by autorefinement; 4000 triangles before, 4120 after".
  std::string summary(const std::string& source) const;
};

//! A repaired and validated input mesh.
struct RepairedInput {
  InputMesh input;
  RepairReport report;
};

//! The file comment's steps on the soup (points, polygons) named `source`.  Throws InvalidInput
//! for a soup that fails checks 1–6 of input_mesh.h (their messages), and for one whose
//! self-intersections could not be removed (the refusal of the file comment).  Tests the
//! command's limits (common/run_limits.h) between steps (a CGAL step runs to its end first).
[[nodiscard]] RepairedInput repair_input_mesh(const std::vector<Point3>& points,
                                              const std::vector<std::vector<std::size_t>>& polygons,
                                              const std::string& source);

//! read_polygon_soup(path) (meshing/inputs/mesh_io.h), then repair_input_mesh.
[[nodiscard]] RepairedInput read_and_repair_input_mesh(const std::string& path);

}  // namespace delmesh
