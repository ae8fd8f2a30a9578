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
//! Constructions are floating point; the combinatorics come from CGAL's exact predicates.

#include <array>
#include <optional>
#include <vector>

#include "common/vec3.h"
#include "meshing/delaunay.h"
#include "solvers/domain.h"
#include "solvers/gradient_cone.h"
#include "symbolic/surface.h"

namespace delmesh {

//! The Voronoi edge dual to a Delaunay triangle: {point + t·direction : t ∈ [t0, t1]}.
struct VoronoiEdge {
  TriangleKey triangle{};
  Vec3 point{};          //!< circumcentre of the triangle
  Vec3 direction{};      //!< unit normal of the triangle
  double t0 = 0, t1 = 0;
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
  //! Whether (u, v) lies in F up to `tolerance` (absolute, world units).
  bool contains(double u, double v, double tolerance) const;
};

//! The clipped Voronoi cell V_p ∩ B.  When V_p is bounded (dimension 3, every cell of p finite),
//! its box is the bounding box of its vertices, the circumcentres of p's cells, enlarged by
//! tolerances::face_membership_relative_tolerance·diag(B) for their rounding and intersected
//! with B, and its half-spaces are the bisectors of p and all its neighbours; otherwise it is
//! computed by clipping B by the bisectors, nearest neighbours first.
struct VoronoiCell {
  VertexId site = -1;
  //! q with a facet pq on ∂V_p: of positive area when clipped; every Delaunay neighbour when built
  //! from the vertices (a facet of no area is then possible, and invalid as a VoronoiFacet).
  std::vector<VertexId> facet_neighbours;
  Domain domain;                           //!< a box holding V_p ∩ B, and the bisector half-spaces
  bool valid = false;
  bool contains(const Vec3& x, double tolerance) const;
};

//! `apexes`, if given, are Delaunay::triangle_apexes(triangle) (known to the caller, e.g. from
//! Delaunay::closed_star); otherwise they are looked up.
VoronoiEdge voronoi_edge(const Delaunay& del, const TriangleKey& triangle, const Box3& box,
                         const std::array<VertexId, 2>* apexes = nullptr);
//! `ring`, if given, holds the third vertices of the triangles pqr (Delaunay::edge_triangles,
//! known to the caller); otherwise they are looked up.
VoronoiFacet voronoi_facet(const Delaunay& del, const EdgeKey& edge, const Box3& box, double rotation,
                           const std::vector<VertexId>* ring = nullptr);
VoronoiCell voronoi_cell(const Delaunay& del, VertexId p, const Box3& box);

//! Whether the point u (solver unknowns) satisfies every half-space of the domain up to tolerance
//! (the box is not tested).
bool half_spaces_contain(const Domain& domain, const std::vector<double>& u, double tolerance);

}  // namespace delmesh
