#pragma once
//! \file restricted_voronoi_mesh.h
//! The restricted Voronoi diagram Vor S|Σ of a point set S and a closed triangle mesh Σ, computed
//! exactly and labelled combinatorially: every restricted cell V_p ∩ Σ is the union of the convex
//! polygons V_p ∩ t over the input triangles t, and every polygon vertex and edge says which
//! features of the input and of Vor S it lies on.
//!
//! Polygon vertices are symbolic, as in geogram's restricted Voronoi diagram: a vertex is
//!  - an input vertex v;
//!  - an edge cut: the point where an input edge uv crosses the bisector plane B(p, q);
//!  - a face cut: the point where the Voronoi edge V_p ∩ V_q ∩ V_r crosses the plane of an input
//!    triangle t.
//! Its coordinates are never stored as the result of a chain of clippings: each decision about a
//! vertex is evaluated from its label and the input doubles alone (homogeneous coordinates by
//! Cramer's rule, no division), in interval arithmetic under CGAL::Protect_FPU_rounding and, when
//! the interval's sign is not certain, again in exact rationals (CGAL::Exact_rational).  This is
//! exact and costs one short expression per decision, where a lazy exact kernel (Epeck) would
//! build a construction DAG whose depth grows with every clipping step.  So every decision is
//! exact: on which side of B(p, q) a vertex lies, whether it lies on it, which edge of a polygon a
//! bisector crosses.  The only rounded values are RvdPolygon::points (for locations and distances
//! in reports); no decision reads them.
//!
//! Candidate cells per triangle t: a Delaunay_triangulation_3 of S (exact predicates) gives every
//! sample's Delaunay neighbours, which are its Voronoi neighbours, so V_p ∩ t is t clipped by the
//! bisectors of p and its neighbours (nearest first; a neighbour q is skipped once |pq|/2 exceeds
//! the polygon's largest distance from p with a relative margin of 1e-6, since then every point of
//! the polygon is strictly nearer to p).  The cells visited for t are those reached from the sample
//! nearest to t's first corner by crossing, in t, an edge of a clipped polygon that lies on a
//! bisector B(p, q) (then q is visited), or by finding a vertex exactly on B(p, q).  The polygons of
//! positive area of t's restricted diagram are adjacent along such edges, so this finds all of
//! them; a cell that meets t only in a segment or a point meets it at a non-generic contact, which
//! the clipping records.
//!
//! Non-generic contacts.  A vertex found exactly on a bisector it is tested against is recorded as
//! a NonGenericContact: an input vertex on B(p, q), an edge cut of B(p, q) on B(p, s) (the
//! Voronoi edge pqs passes through an input edge), a face cut of pqr on B(p, s) (the Voronoi
//! vertex pqrs lies on Σ).  Such a vertex is kept in p's polygon (ties go to the cell being
//! clipped), so cells are closed sets and adjacent polygons may overlap in a segment or a point
//! there; the diagram is then not in general position and callers report it as such.

#include <array>
#include <cstddef>
#include <limits>
#include <ostream>
#include <vector>

#include "common/enum_names.h"
#include "meshing/core/surface_mesh.h"

namespace delmesh {

//! The kind of a polygon vertex (file comment).
enum class RvdVertexKind { input_vertex, edge_cut, face_cut };
constexpr auto enum_names(RvdVertexKind) {
  return name_table<RvdVertexKind>("RvdVertexKind", {{RvdVertexKind::input_vertex, "input_vertex"},
                                                     {RvdVertexKind::edge_cut, "edge_cut"},
                                                     {RvdVertexKind::face_cut, "face_cut"}});
}
inline std::ostream& operator<<(std::ostream& out, RvdVertexKind kind) { return write_enum(out, kind); }

inline constexpr std::size_t rvd_none = std::numeric_limits<std::size_t>::max();

//! A polygon vertex by its label, the same in every polygon and cell that has it (the key that
//! glues pieces together).  Sample indices are positions in the sample vector; input indices are
//! SurfaceMesh vertex and face indices.
//!  - input_vertex: input = {v, none}; sites all none.
//!  - edge_cut: input = {u, w}, u < w the input edge; sites = {p, q, none}, p < q, the bisector.
//!  - face_cut: input = {t, none}, t the input face; sites = {p, q, r}, p < q < r, the Voronoi edge.
struct RvdVertex {
  RvdVertexKind kind = RvdVertexKind::input_vertex;
  std::array<std::size_t, 2> input{rvd_none, rvd_none};
  std::array<std::size_t, 3> sites{rvd_none, rvd_none, rvd_none};

  friend bool operator==(const RvdVertex& a, const RvdVertex& b) {
    return a.kind == b.kind && a.input == b.input && a.sites == b.sites;
  }
  friend bool operator!=(const RvdVertex& a, const RvdVertex& b) { return !(a == b); }
  friend bool operator<(const RvdVertex& a, const RvdVertex& b) {
    if (a.kind != b.kind) return a.kind < b.kind;
    if (a.input != b.input) return a.input < b.input;
    return a.sites < b.sites;
  }
};

//! What a polygon edge lies on: an input edge {u, w} (u < w; on_bisector false), or the bisector
//! B(p, other) of the cell's site p and the sample `other` (on_bisector true; then b is none).
struct RvdEdgeSupport {
  bool on_bisector = false;
  std::size_t a = rvd_none, b = rvd_none;  //!< {u, w} or {other, none}

  friend bool operator==(const RvdEdgeSupport& x, const RvdEdgeSupport& y) {
    return x.on_bisector == y.on_bisector && x.a == y.a && x.b == y.b;
  }
  friend bool operator<(const RvdEdgeSupport& x, const RvdEdgeSupport& y) {
    if (x.on_bisector != y.on_bisector) return x.on_bisector < y.on_bisector;
    if (x.a != y.a) return x.a < y.a;
    return x.b < y.b;
  }
};

//! One piece V_p ∩ t of a restricted cell: a convex polygon with at least three vertices, in the
//! order of t's corners (counter-clockwise seen from t's normal).  edges[i] joins vertices[i] and
//! vertices[(i + 1) % n]; points[i] is vertices[i] rounded to doubles.
struct RvdPolygon {
  std::size_t site = rvd_none;
  std::size_t face = rvd_none;
  std::vector<RvdVertex> vertices;
  std::vector<RvdEdgeSupport> edges;
  std::vector<std::array<double, 3>> points;
};

//! The kinds of non-generic contact (file comment).
enum class RvdContactKind { input_vertex_on_bisector, voronoi_edge_through_input_edge, voronoi_vertex_on_surface };
constexpr auto enum_names(RvdContactKind) {
  return name_table<RvdContactKind>(
      "RvdContactKind", {{RvdContactKind::input_vertex_on_bisector, "input_vertex_on_bisector"},
                         {RvdContactKind::voronoi_edge_through_input_edge, "voronoi_edge_through_input_edge"},
                         {RvdContactKind::voronoi_vertex_on_surface, "voronoi_vertex_on_surface"}});
}
inline std::ostream& operator<<(std::ostream& out, RvdContactKind kind) { return write_enum(out, kind); }

//! A vertex found exactly on a bisector B(p, s): `vertex` (its label), the sites of the Voronoi
//! face it lies on (sorted: p and s for an input vertex, three for an input edge, four for a
//! Voronoi vertex), and its location rounded to doubles.
struct RvdContact {
  RvdContactKind kind = RvdContactKind::input_vertex_on_bisector;
  RvdVertex vertex;
  std::vector<std::size_t> sites;
  std::array<double, 3> location{};
};

//! Vor S|Σ as pieces.
struct RestrictedVoronoiMesh {
  //! cells[p]: the pieces of V_p ∩ Σ, by increasing face index; empty if V_p does not meet Σ in
  //! a polygon of positive area.
  std::vector<std::vector<RvdPolygon>> cells;
  //! Every non-generic contact found, once per (kind, sites, input vertex, edge or face), sorted so.
  std::vector<RvdContact> contacts;
  std::size_t sign_tests = 0;         //!< vertex-against-bisector decisions
  std::size_t exact_evaluations = 0;  //!< those whose interval sign was not certain
};

//! Vor S|Σ for the samples `samples` and the triangle mesh `mesh`.
//! Preconditions (PreconditionViolation otherwise): the samples are distinct finite points; `mesh`
//! is a closed triangle mesh (every halfedge has a face, every face three vertices) without
//! removed elements, with finite coordinates.  Σ need not be connected; nothing is assumed of its
//! embedding beyond that (a self-intersecting mesh gives each triangle's pieces all the same).
//! Time: about (triangles + samples) times the pieces per triangle times the Delaunay degree.
RestrictedVoronoiMesh restricted_voronoi_mesh(const std::vector<Point3>& samples, const SurfaceMesh& mesh);

//! The point of `v` rounded to doubles (the exact point is a rational; this is its nearest
//! double coordinates up to one rounding of an interval's midpoint).
std::array<double, 3> rvd_point(const RvdVertex& v, const std::vector<Point3>& samples, const SurfaceMesh& mesh);

}  // namespace delmesh
