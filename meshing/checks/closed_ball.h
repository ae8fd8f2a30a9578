#pragma once
//! \file closed_ball.h
//! The closed-ball property of a sample set S on a piecewise-linear surface Σ (a closed triangle
//! mesh), checked directly on the exact restricted Voronoi diagram
//! (meshing/voronoi/restricted_voronoi_mesh.h).
//!
//! Theorem (Edelsbrunner and Shah, Triangulating topological spaces, 1997; Theorem 2.1 of the
//! paper).  Let Σ be a compact 2-manifold without boundary in R³ and S a finite point set such
//! that Vor S and Σ are in general position: Σ contains no Voronoi vertex, and every Voronoi face
//! of dimension k meets Σ transversally, in a set of dimension k − 1.  If every Voronoi face F of
//! dimension k meets Σ in the empty set or in a closed (k − 1)-ball — every cell V_p in a closed
//! disk, every facet in one simple arc, every edge in a single point — then the restricted
//! Delaunay triangulation Del S|Σ (the triangles pqr whose Voronoi edge V_p ∩ V_q ∩ V_r meets Σ)
//! is homeomorphic to Σ.
//!
//! What is decided, from the combinatorial labels of Vor S|Σ alone (so exactly):
//!  - general position: no input vertex on a bisector, no Voronoi edge through an input edge, no
//!    Voronoi vertex on Σ.  For a PL surface these are the contacts that break transversality: a
//!    bisector containing a triangle, or a Voronoi edge in a triangle's plane, puts input vertices
//!    or edge cuts on bisectors and is reported through them.  Any such contact makes the status
//!    non_generic, listed with its location: the theorem's assumption fails there and nothing is
//!    claimed, whatever the faces look like;
//!  - every cell V_p ∩ Σ, glued from its polygons along shared vertices and edges: an edge on an
//!    input edge is interior (two polygons), an edge on a bisector is boundary (one); the cell is a
//!    closed disk iff it is connected, every edge has one or two polygons, the link of every
//!    vertex is one path or one cycle, the boundary is one cycle, and V − E + F = 1;
//!  - every restricted facet V_p ∩ V_q ∩ Σ, the polygon edges on B(p, q): one simple arc iff they
//!    form a connected graph with every degree at most 2 and exactly two vertices of degree 1;
//!  - every Voronoi edge V_p ∩ V_q ∩ V_r ∩ Σ: its face cuts, which must be at most one.
//! Voronoi vertices must miss Σ, which is the first item.
//!
//! Under general position these are the conditions of the theorem, exactly.  The rounded
//! points (witnesses, locations) are for reports; no decision reads them.

#include <array>
#include <cstddef>
#include <optional>
#include <ostream>
#include <vector>

#include <nlohmann/json.hpp>

#include "common/enum_names.h"
#include "meshing/core/surface_mesh.h"
#include "meshing/voronoi/restricted_voronoi_mesh.h"

namespace delmesh {

enum class ClosedBallStatus {
  holds,       //!< general position, and every Voronoi face meets Σ in nothing or a closed ball
  violated,    //!< general position, and some face fails (violations lists them)
  non_generic  //!< a non-generic contact was found (contacts lists them); nothing is claimed
};
constexpr auto enum_names(ClosedBallStatus) {
  return name_table<ClosedBallStatus>("ClosedBallStatus", {{ClosedBallStatus::holds, "holds"},
                                                           {ClosedBallStatus::violated, "violated"},
                                                           {ClosedBallStatus::non_generic, "non_generic"}});
}
inline std::ostream& operator<<(std::ostream& out, ClosedBallStatus status) { return write_enum(out, status); }

//! What is wrong with one Voronoi face's intersection with Σ.
enum class ClosedBallDefect {
  cell_not_manifold,  //!< an edge with three or more polygons, or a vertex whose link is not one path or cycle
  cell_components,    //!< the cell is not connected (`components` pieces)
  cell_closed,        //!< a connected closed surface: the cell holds a whole component of Σ
  cell_annulus,       //!< connected, two boundary cycles, V − E + F = 0
  cell_not_disk,      //!< connected and manifold, but another surface (see euler_characteristic, boundary_cycles)
  facet_closed_loop,  //!< the facet meets Σ in closed curves only (one cycle, or with components > 1 several)
  facet_components,   //!< the facet meets Σ in `components` pieces
  facet_branching,    //!< a vertex of the facet's curve has three or more of its edges
  edge_points         //!< the Voronoi edge meets Σ in `points` ≥ 2 points
};
constexpr auto enum_names(ClosedBallDefect) {
  return name_table<ClosedBallDefect>("ClosedBallDefect",
                                      {{ClosedBallDefect::cell_not_manifold, "cell_not_manifold"},
                                       {ClosedBallDefect::cell_components, "cell_components"},
                                       {ClosedBallDefect::cell_closed, "cell_closed"},
                                       {ClosedBallDefect::cell_annulus, "cell_annulus"},
                                       {ClosedBallDefect::cell_not_disk, "cell_not_disk"},
                                       {ClosedBallDefect::facet_closed_loop, "facet_closed_loop"},
                                       {ClosedBallDefect::facet_components, "facet_components"},
                                       {ClosedBallDefect::facet_branching, "facet_branching"},
                                       {ClosedBallDefect::edge_points, "edge_points"}});
}
inline std::ostream& operator<<(std::ostream& out, ClosedBallDefect defect) { return write_enum(out, defect); }

//! One Voronoi face whose intersection with Σ is not a closed ball.
struct ClosedBallViolation {
  int dimension = 3;               //!< of the Voronoi face: 3 cell, 2 facet, 1 edge
  std::vector<std::size_t> sites;  //!< sorted sample indices: {p}, {p, q}, {p, q, r}
  ClosedBallDefect defect = ClosedBallDefect::cell_not_disk;
  std::size_t components = 0;      //!< connected pieces of the intersection (cells and facets)
  long euler_characteristic = 0;   //!< V − E + F of the cell (cells)
  std::size_t boundary_cycles = 0; //!< cycles of the cell's boundary (cells)
  std::size_t points = 0;          //!< points of the intersection (edges)
  //! The point of the intersection farthest from the face's first site (a vertex of its
  //! polygons, rounded), where DelMesh-style refinement inserts; and that distance.
  std::array<double, 3> witness{};
  double witness_distance = 0;
};

struct [[nodiscard]] ClosedBallResult {
  ClosedBallStatus status = ClosedBallStatus::holds;
  std::size_t cells_checked = 0;   //!< samples whose cell meets Σ
  std::size_t facets_checked = 0;  //!< Voronoi facets that meet Σ
  std::size_t edges_checked = 0;   //!< Voronoi edges that meet Σ
  std::vector<ClosedBallViolation> violations;  //!< cells, then facets, then edges, each by sites
  std::vector<RvdContact> contacts;             //!< the non-generic contacts (restricted_voronoi_mesh.h)
  //! Del S|Σ: the sorted site triples of the Voronoi edges that meet Σ, sorted.
  std::vector<std::array<std::size_t, 3>> restricted_delaunay;
  std::size_t polygons = 0;           //!< pieces V_p ∩ t
  std::size_t sign_tests = 0, exact_evaluations = 0;
  double seconds = 0;                 //!< of the whole check, Vor S|Σ included
};

//! The check of the file comment on Vor S|Σ for `samples` and `mesh`.  Preconditions as for
//! restricted_voronoi_mesh() (PreconditionViolation otherwise).
ClosedBallResult closed_ball_check(const std::vector<Point3>& samples, const SurfaceMesh& mesh);

//! The same on a diagram already computed from `samples` (`seconds` then covers this call only).
ClosedBallResult closed_ball_check(const RestrictedVoronoiMesh& diagram, const std::vector<Point3>& samples);

//! How the triangles of a mesh compare with result.restricted_delaunay, as sets of vertex triples.
struct RestrictedDelaunayComparison {
  bool equal = false;                     //!< the two sets are equal (and the mesh has no repeated triangle)
  std::size_t only_restricted_delaunay = 0;  //!< triples of Del S|Σ that are not a triangle of the mesh
  std::size_t only_mesh = 0;                 //!< triangles of the mesh (counted with repetition) not in Del S|Σ
};

//! Compares the triangles of `output`, whose vertices in index order are the samples the result was
//! computed for, with result.restricted_delaunay.  A face that is not a triangle counts in only_mesh.
//! Precondition: `output` has no removed elements (PreconditionViolation).
RestrictedDelaunayComparison compare_with_restricted_delaunay(const ClosedBallResult& result, const SurfaceMesh& output);

//! {status, cells, facets, edges, polygons, violations: {count, by_kind: {defect: n}, first: [{kind,
//!  sites, witness, witness_distance, components, euler_characteristic, boundary_cycles, points}]},
//!  non_generic: {count, by_kind: {contact kind: n}, first: [{kind, sites, location}]},
//!  restricted_delaunay_triangles, sign_tests, exact_evaluations, seconds}; `first` lists at most
//! `listed` entries.
nlohmann::json closed_ball_json(const ClosedBallResult& result, std::size_t listed);

}  // namespace delmesh
