#pragma once
//! \file sharp_features.h
//! The sharp features of a triangle mesh: sharp edges, corners and the feature curves between
//! them, as the protection of a piecewise-linear input needs them (meshing/inputs/protecting_balls.h).
//!
//! ## Sharp edges
//! An interior edge is *sharp* when the angle between the normals of its two faces exceeds the
//! feature angle θ (degrees, 0 < θ < 180; default default_feature_angle_deg = 60°).  The normals
//! are n₁ = (b − a) × (c − a) of each face, oriented by the face's own orientation (a halfedge
//! mesh traverses a shared edge in opposite directions from its two faces, so the two normals
//! are consistently oriented); their angle is π minus the dihedral angle of the edge, 0 on a
//! flat edge.  The test is
//!     ⟨n₁, n₂⟩ < c · |n₁| |n₂|,    c = cos θ,
//! decided exactly: by sign cases and the squares (⟨n₁, n₂⟩² against c²|n₁|²|n₂|²) in interval
//! arithmetic from the input doubles, and in exact rationals when the interval's sign is
//! uncertain.  c is cos θ rounded to a double, except for θ = 60°, 90°, 120°, where it is the
//! exact ½, 0, −½ (so an edge of exactly 60° between its normals, e.g. of a hexagonal prism, is
//! not sharp at the default).  An edge next to a face with a zero normal (a degenerate triangle)
//! is sharp (its angle is undefined, so it is kept as a feature).  A border edge (in one face
//! only) is always a feature edge.
//!
//! Why 60°: a feature is a place where the normal of a piecewise-linear surface jumps so far that
//! no sample spacing makes the surface look smooth there; the creases of CAD parts (fandisk,
//! cube: 90°) are far above 60°, while the normal jumps between neighbouring faces of a
//! tessellated smooth surface at the resolutions remeshed here stay well below it.  60° is also
//! the default of CGAL's feature detection for polyhedral domains, so both agree on what is a
//! feature.
//!
//! ## Corners
//! A vertex is a *corner* when it is incident to exactly 1 or at least 3 feature edges (an end of
//! a curve, or where curves meet), or when it is folded (meshing/inputs/folded_vertices.h: no direction
//! is faced by all of its faces, so no smooth-surface check can ever be clean there), whatever
//! its number of feature edges (a folded vertex with none is an isolated corner).
//!
//! ## Feature curves
//! The feature edges form a graph whose vertices have degree 2 except at corners; it splits into
//! polylines of input edges, each from a corner to a corner (possibly the same one), and closed
//! polylines through no corner.  Order (deterministic for a given mesh): the open curves first,
//! from each corner in ascending vertex index, along its feature edges in ascending edge index
//! (a curve between two corners is listed once, from the first corner reached); then the closed
//! curves without a corner, by their smallest vertex index, each starting at that vertex and going
//! first to the smaller-indexed of its two neighbours on the curve.

#include <array>
#include <cstddef>
#include <vector>

#include <nlohmann/json.hpp>

#include "meshing/core/surface_mesh.h"

namespace delmesh {

//! The default feature angle (degrees) of detect_features: the angle between two faces' normals
//! above which their shared edge is sharp (see the file comment for why 60°).
inline constexpr double default_feature_angle_deg = 60.0;

//! One feature curve: a polyline of input edges.
struct FeatureCurve {
  //! The vertices in order along the curve; for a closed curve the first vertex is repeated at
  //! the end, so vertices.size() == edges.size() + 1 always.
  std::vector<SurfaceMesh::Vertex_index> vertices;
  //! edges[i] joins vertices[i] and vertices[i + 1].
  std::vector<SurfaceMesh::Edge_index> edges;
  //! True when the curve returns to its start (a loop through one corner, or a curve without any).
  bool closed = false;
  //! True for a closed curve through no corner (its start is chosen as the file comment says).
  bool without_corner = false;
};

//! The features of a mesh at one feature angle.
struct FeatureSet {
  double angle_deg = default_feature_angle_deg;  //!< the feature angle used
  //! Every feature edge (sharp interior edges and border edges), ascending by index.
  std::vector<SurfaceMesh::Edge_index> feature_edges;
  std::size_t sharp_edges = 0;   //!< feature edges that are interior (two faces) and sharp
  std::size_t border_edges = 0;  //!< feature edges that are border edges
  //! The corners (file comment), ascending by index.
  std::vector<SurfaceMesh::Vertex_index> corners;
  std::size_t folded_corners = 0;  //!< corners that are folded vertices
  std::vector<FeatureCurve> curves;
  std::size_t closed_curves = 0;          //!< curves with closed == true
  std::size_t curves_without_corner = 0;  //!< curves with without_corner == true

  //! Whether edge e of the mesh is a feature edge (binary search).
  bool is_feature_edge(SurfaceMesh::Edge_index e) const;
  //! Whether v is a corner (binary search).
  bool is_corner(SurfaceMesh::Vertex_index v) const;
};

//! The feature edges of a mesh as segments, for the question the Smooth check of a
//! piecewise-linear input asks (meshing/checks/smooth.h): does the Voronoi facet V_p ∩ V_q of two
//! samples meet a feature edge?
//!
//! The criterion (facet_meets_feature_edge).  A feature edge uw *meets the facet of pq* when it
//! crosses the bisector plane B(p, q) strictly (u and w on opposite sides, neither on it) at a
//! point x — the edge cut of B(p, q) on uw — that lies in the closed Voronoi cell V_p, i.e.
//! |x − p|² ≤ |x − s|² for every other sample s (x is then in V_q as well, being on B(p, q)).
//! When Vor S and Σ are in general position (no input vertex on a bisector, no Voronoi edge
//! through an input edge), these are exactly the edge cuts of B(p, q) on a feature edge that are
//! vertices of the polygons of the restricted Voronoi diagram Vor S|Σ
//! (meshing/voronoi/restricted_voronoi_mesh.h, which creates an edge cut for a strict crossing);
//! at a tie the cut is counted here, in the closed cell, whatever label the diagram gives it.  V_p is the intersection of the half-spaces of p's Voronoi neighbours, which
//! are among its Delaunay neighbours, so `others` need only hold those.  Every decision is exact:
//! the cut is kept in homogeneous coordinates and each sign is evaluated in interval arithmetic
//! and, when not certain, in exact rationals, from the input doubles.
class FeatureEdges {
 public:
  //! No feature edges (features off): no facet meets one.
  FeatureEdges() = default;
  //! The feature edges of `features` (detect_features of `mesh`) as segments, copied.
  FeatureEdges(const SurfaceMesh& mesh, const FeatureSet& features);

  bool empty() const { return segments_.empty(); }
  std::size_t size() const { return segments_.size(); }
  //! The feature angle of the FeatureSet they came from (degrees; 0 for none).
  double angle_deg() const { return angle_deg_; }

  //! Whether some feature edge meets the facet of the samples p and q (the criterion above);
  //! `others` holds the other samples that bound V_p (at least p's Voronoi neighbours other than
  //! q; more are allowed).  Precondition: p ≠ q.  Time: linear in the feature edges.
  bool facet_meets_feature_edge(const Point3& p, const Point3& q, const std::vector<Point3>& others) const;

 private:
  std::vector<std::array<Point3, 2>> segments_;
  double angle_deg_ = 0;
};

//! The exact decision of the file comment for the normals (b − a) × (c − a) and (e − d) × (f − d)
//! of the triangles (a, b, c) and (d, e, f) at the feature angle angle_deg: true when the angle
//! between the normals exceeds it, or a normal is zero.
//! Precondition: 0 < angle_deg < 180 (throws PreconditionViolation otherwise).
bool normals_differ_by_more_than(const Point3& a, const Point3& b, const Point3& c, const Point3& d,
                                 const Point3& e, const Point3& f, double angle_deg);

//! The features of `mesh` at the feature angle `angle_deg` (file comment), with the given folded
//! vertices (as folded_vertices(mesh) returns them; any order, duplicates ignored) as corners.
//! Any Surface_mesh (border edges are features; isolated vertices are never corners unless listed
//! as folded).  Precondition: 0 < angle_deg < 180, the folded vertices are vertices of `mesh`
//! (throws PreconditionViolation otherwise).  O(E log E) for E edges plus the exact signs.
FeatureSet detect_features(const SurfaceMesh& mesh, double angle_deg,
                           const std::vector<SurfaceMesh::Vertex_index>& folded);

//! The same with the folded vertices computed (folded_vertices(mesh); tests the command's limits
//! as that does).
FeatureSet detect_features(const SurfaceMesh& mesh, double angle_deg = default_feature_angle_deg);

//! The counts of a feature set for the statistics: {angle_deg, sharp_edges, curves, closed_curves,
//! corners, folded_corners}.
nlohmann::json features_json(const FeatureSet& features);

}  // namespace delmesh
