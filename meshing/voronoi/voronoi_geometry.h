#pragma once
//! \file voronoi_geometry.h
//! The Voronoi faces of Vor S as convex polytopes given by half-spaces — exactly what the solvers
//! take (solvers/domain.h).  Σ lies strictly inside the box B, so every face is clipped to B
//! and no intersection with Σ is lost; no dummy points are added.
//!
//! Choices (the paper leaves them open):
//! - V_p = B ∩ ⋂_{q ∈ N(p)} {x : |x−p| ≤ |x−q|} with N(p) the Delaunay neighbours of p.  This
//!   description holds in every dimension of Del S (a degenerate, e.g. coplanar, sample set
//!   included), so unbounded cells, facets and edges are handled uniformly.
//! - The facet F of a Delaunay edge pq lies in the bisector plane Π of pq with frame
//!   (o = (p+q)/2, a, b), a, b orthonormal ⟂ q−p, rotated in Π by a caller-supplied angle (the
//!   mesher passes a seeded pseudo-random angle, so that d = a is a generic in-plane direction
//!   for CurveCritical); F = Π ∩ V_p, computed by clipping the polygon Π ∩ B by the bisectors of
//!   p and the third vertices of the triangles pqr (in dimension 3; by all of N(p) below).
//! - The edge of a Delaunay triangle pqr is its support line c + t n (c the circumcentre, n the
//!   unit normal (q−p)×(r−p)/|…| of pqr with p < q < r by id) intersected with V_p: in dimension
//!   3 the segment between the circumcentres of pqr's two cells, or the ray from the finite one
//!   away from its apex (pqr on the hull), clipped by B; in dimension 2 the line clipped by B
//!   and by the bisectors of p's neighbours.
//!
//! One diagram.  Constructions are floating point (the combinatorics come from CGAL's exact
//! predicates), and each Voronoi vertex — the circumcentre of a finite Delaunay cell — is
//! computed once, by voronoi_vertex(), from its four sites in increasing id order, so every face
//! at it uses the same point:
//! - an edge's end at a Voronoi vertex is that point (voronoi_edge_ends(); its parameter is the
//!   point's projection onto the edge's line), so the sign of E at a vertex, on which §5.1
//!   decides, is the same for its four edges;
//! - the half-plane of the facet F_pq for the triangle pqr is the bisector of p and r, moved
//!   outwards just enough to hold both vertices of pqr's edge (projected into Π), so F_pq holds
//!   every vertex of its boundary and the facets around a Voronoi edge all reach it;
//! - the cell V_p's box holds its vertices, and its half-space for a neighbour q is the bisector
//!   of p and q moved outwards just enough to hold the vertices of the facet F_pq.
//! The faces are therefore closed sets that overlap on the shared vertices and edges of the
//! computed diagram: a point of Σ on a shared vertex or edge lies in every face that contains
//! it, up to the rounding of one projection.  The moves are the errors of the circumcentres
//! (zero in exact arithmetic), so the faces are those of Vor S up to them.  These errors are not
//! a few units in the last place: for four nearly cospherical sites (a sliver) the formula loses
//! as many digits as the cell is flat, and the double circumcentre can be off by many times
//! tolerances::face_membership_relative_tolerance · diag(B).  certified_voronoi_vertex() therefore
//! gives each Voronoi vertex v a certified error radius ρ(v) ≥ |v − v*| (v* the exact
//! circumcentre), and every shortcut that compares faces built in different ways widens its
//! margin by the radii of the vertices involved (see each one's contract).  Here:
//! - V_p's box, built from the Voronoi vertices of p's cells (bounded V_p), is their bounding box
//!   enlarged by max(face_membership_relative_tolerance · diag(B), 2ρ), ρ the largest radius of
//!   those vertices: V_p = conv{v*} lies in the bounding box of the v enlarged by ρ, and the
//!   second term covers the rounding of the enlargement itself whenever it exceeds the first.
//!   The box read off the Delaunay dual (unbounded V_p) also uses the points where the computed
//!   Voronoi edges cross ∂B, which the radii do not bound; it is used only when 2ρ is within the
//!   membership margin, and V_p is clipped from the bisectors (which no circumcentre enters)
//!   otherwise.
//! - The half-spaces of the faces are the exact bisectors (up to the rounding of one dot product)
//!   moved outwards only, so each computed face holds the exact one up to that rounding, whatever
//!   the circumcentres' errors.
//! The rays and the faces of an unbounded cell (pq on the convex hull of S) are cut by B.

#include <array>
#include <optional>
#include <vector>

#include "common/vec3.h"
#include "meshing/voronoi/delaunay.h"
#include "solvers/domain.h"
#include "solvers/gradient_cone.h"
#include "symbolic/surface.h"

namespace delmesh {

//! The Voronoi vertex dual to a finite Delaunay cell: the circumcentre of its four sites,
//! computed from the sites in increasing id order (the same point for every face at it), by the
//! formula in doubles — or, when its certified error (certified_voronoi_vertex()) exceeds
//! tolerances::voronoi_vertex_exact_relative_error of its distance to the sites (a nearly flat
//! cell), constructed exactly and rounded to doubles.  The
//! last ones computed on each thread are kept under (Delaunay::serial(), ids) and returned again.
//! \pre the four ids are distinct vertices of Del S, not coplanar.
Vec3 voronoi_vertex(const Delaunay& del, std::array<VertexId, 4> cell);

//! A Voronoi vertex with a certified bound on its error.
struct VoronoiVertex {
  Vec3 centre{};    //!< voronoi_vertex() of the cell, bit for bit
  double radius{};  //!< ρ ≥ |centre − c*|, c* the exact circumcentre of the four sites (+∞ if unknown)
};
//! voronoi_vertex() of the cell with its error radius ρ.  The circumcentre formula
//! c = p + (|a|² b×c′ + |b|² c′×a + |c′|² a×b) / (2⟨a, b×c′⟩), a = q−p, b = r−p, c′ = s−p, is
//! evaluated once more in interval arithmetic (CGAL::Interval_nt under upward rounding) from the
//! sites, which are exact doubles: the box it returns holds c*, so the distance from `centre` to
//! the box's farthest corner, rounded upwards, bounds |centre − c*|.  When the interval of the
//! denominator holds 0 (the four sites are coplanar up to the rounding of the intervals) c* is
//! constructed exactly (CGAL's exact kernel) and ρ is |centre − c*| rounded upwards.  A cheaper
//! static bound (the standard rounding model applied to the formula, in doubles; far looser for
//! flat cells) is tried first, and returned when it is at most `enough`: callers that only ask
//! whether ρ is below a threshold pass it.  The radius is kept with the centre (one double per
//! kept vertex) and computed on first request.
//! \pre as for voronoi_vertex().
VoronoiVertex certified_voronoi_vertex(const Delaunay& del, std::array<VertexId, 4> cell, double enough = 0);

//! The Voronoi edge dual to a Delaunay triangle: {point + t·direction : t ∈ [t0, t1]}.
//! (The members are ordered so that the ids and flags share the last 16 bytes: 80 in all.)
struct VoronoiEdge {
  Vec3 point{};          //!< circumcentre of the triangle
  Vec3 direction{};      //!< unit normal of the triangle
  double t0 = 0, t1 = 0;
  TriangleKey triangle{};
  bool at_vertex0 = false, at_vertex1 = false;  //!< endpoint is a Voronoi vertex (not on ∂B)
  bool valid = false;    //!< false if the clipped edge is empty
  //! The edge is inside B but its computed ends cross (t0 ≥ t1 before clipping): numerically a
  //! single point, at(t0) = at(t1), e.g. where five or more samples are cospherical.  Then
  //! valid = false and t0 = t1 hold the point's parameter.
  bool degenerate = false;
  Vec3 at(double t) const { return {point[0] + t * direction[0], point[1] + t * direction[1], point[2] + t * direction[2]}; }
};

//! The Voronoi facet dual to a Delaunay edge pq, in its plane frame.
struct VoronoiFacet {
  EdgeKey edge{};
  Vec3 origin{}, a{}, b{}, normal{};               //!< x = origin + u a + v b; normal ∥ q−p
  std::vector<std::array<double, 2>> polygon;      //!< counter-clockwise (u, v)
  Domain domain;                                   //!< bounding box ∩ edge half-planes
  bool valid = false;                              //!< false if F is empty or has no area
  //! F is not empty but has (numerically) no area: valid = false, and `polygon` keeps the
  //! points the clipping left, whose hull contains the computed F.
  bool degenerate = false;
  Vec3 world(double u, double v) const;
  //! The plane frame as a chart x = origin + u a + v b (for solvers/gradient_cone.h).
  AffineChart chart() const { return AffineChart{origin, {a, b}}; }
  //! (u, v) of the orthogonal projection of x onto Π.
  std::array<double, 2> plane_coordinates(const Vec3& x) const;
  //! The bounding box in (u, v) of `polygon`, widened by `margin` on every side, without
  //! half-planes: for a degenerate facet, a domain that holds F (up to the rounding the margin
  //! covers).  Throws PreconditionViolation if the polygon is empty.
  Domain polygon_hull(double margin) const;
  //! Whether (u, v) lies in F up to `tolerance` (absolute, world units).
  bool contains(double u, double v, double tolerance) const;
};

//! The clipped Voronoi cell V_p ∩ B.  In dimension 3 its half-spaces are the bisectors of p and
//! all its neighbours, and its box is the bounding box of the vertices of V_p ∩ B, enlarged by
//! tolerances::face_membership_relative_tolerance·diag(B) and intersected with B: when V_p is
//! bounded (every cell of p finite) those of V_p (voronoi_vertex() of p's cells); otherwise
//! read off the Delaunay dual: the Voronoi vertices in B, the points where V_p's edges
//! (segments, and rays for the triangles of p on the convex hull) cross ∂B, and the ends of the
//! parts of B's edges inside V_p.  Below dimension 3, or if a Voronoi vertex is not finite, it is
//! computed by clipping B by the bisectors, nearest neighbours first (its half-spaces then those
//! of the facets left).  Either way the half-space of each neighbour q is then moved outwards to
//! hold the Voronoi vertices of F_pq, and the box to hold the cell's Voronoi vertices in B.
struct VoronoiCell {
  VertexId site = -1;
  //! q with a facet pq on ∂V_p: of positive area when clipped; every Delaunay neighbour in
  //! dimension 3 otherwise (a facet of no area in B is then possible, and invalid as a
  //! VoronoiFacet).
  std::vector<VertexId> facet_neighbours;
  Domain domain;                           //!< a box holding V_p ∩ B, and the bisector half-spaces
  bool valid = false;
  bool contains(const Vec3& x, double tolerance) const;
};

//! The line of the dual edge of `triangle`: an edge with `triangle` set and, when the triangle
//! has a normal in doubles, `point` (its circumcentre) and `direction` (its unit normal), as
//! voronoi_edge() sets them; t0 = t1 = 0, not valid.  A function of the triangle's points only.
VoronoiEdge voronoi_edge_line(const Delaunay& del, const TriangleKey& triangle);
//! The clipped dual edge of `triangle`: voronoi_edge_line() with its extent in Del S and `box`.
//! `apexes`, if given, are Delaunay::triangle_apexes(triangle) (known to the caller, e.g. from
//! Delaunay::closed_star); otherwise they are looked up.
//! `shared`, if given, receives voronoi_edge_ends() of the edge when it is valid.
VoronoiEdge voronoi_edge(const Delaunay& del, const TriangleKey& triangle, const Box3& box,
                         const std::array<VertexId, 2>* apexes = nullptr, std::array<Vec3, 2>* shared = nullptr);
//! The ends of an edge built by voronoi_edge(): at(t0) and at(t1), except that an end at a Voronoi
//! vertex is voronoi_vertex() of its cell (on the line up to rounding), the point shared with
//! the other faces at it.  `apexes` as for voronoi_edge().
std::array<Vec3, 2> voronoi_edge_ends(const Delaunay& del, const VoronoiEdge& e,
                                      const std::array<VertexId, 2>* apexes = nullptr);
//! `ring`, if given, holds the triangles pqr around the edge with their apexes
//! (Delaunay::edge_ring, known to the caller, in any order); otherwise it is looked up.
VoronoiFacet voronoi_facet(const Delaunay& del, const EdgeKey& edge, const Box3& box, double rotation,
                           const std::vector<Delaunay::RingTriangle>* ring = nullptr);
VoronoiCell voronoi_cell(const Delaunay& del, VertexId p, const Box3& box);
//! The same cell from p's Delaunay cells `cells` (Delaunay::incident_cells(p)) and neighbours
//! `neighbours` (Delaunay::neighbours(p)), known to the caller: it then reads only the points of
//! `del`, never its combinatorial structure, so it may run on one thread while another walks
//! `del` (a walk marks CGAL's cells as it goes) as long as neither changes it.
VoronoiCell voronoi_cell(const Delaunay& del, VertexId p, const Box3& box,
                         const std::vector<std::array<VertexId, 4>>& cells, const std::vector<VertexId>& neighbours);

//! Whether the point u (solver unknowns) satisfies every half-space of the domain up to tolerance
//! (the box is not tested).
bool half_spaces_contain(const Domain& domain, const std::vector<double>& u, double tolerance);

}  // namespace delmesh
