#pragma once
//! \file mesh_oracle.h
//! The surface oracle (meshing/core/surface_oracle.h) of a piecewise-linear surface: Σ a closed,
//! 2-manifold triangle mesh without self-intersections, every face oriented outward (as
//! meshing/inputs/input_mesh.h delivers it), inside a box B.  Remeshing such a surface with DelMesh is
//! §7 of the paper (Fig. 13).
//!
//! Exactness.  Every decision that is a sign — on which side of a face's plane a point lies,
//! whether a segment meets a face, which side of a facet's plane a mesh vertex lies on, which way
//! a face faces relative to a direction, which of two vertices is higher in a direction, inside
//! or outside — is an exact predicate on the input doubles: CGAL's filtered predicates of the
//! Epick kernel (orientation, do_intersect) or a determinant or dot product
//! evaluated in interval arithmetic and, if its sign is not certain, in exact rationals.  Only the
//! points the oracle returns (a crossing of a segment and a face, of a mesh edge and a plane) are
//! constructed in double precision; they lie on Σ up to rounding.  Where a plane or a direction is
//! given, it is the one the doubles describe: the plane of the facet frame (o, a, b) is the plane
//! through the double points o, o + a, o + b.
//!
//! Symbolic perturbation.  A mesh vertex exactly on a facet's plane counts as lying on its
//! positive side (the side of a × b), i.e. the plane is moved by an infinitesimal amount against
//! its normal; two vertices of exactly equal height in a direction are ordered by their index
//! (the one with the larger index is higher); a face exactly parallel to a direction counts as
//! facing it.  So every section of Σ by a facet's plane is a disjoint union of closed polylines,
//! and every silhouette a union of closed edge paths.
//!
//! The six primitives of §5.2 on a PL surface:
//!  - surface_line(p, v, t0, t1): every point where the segment meets Σ.  A transversal crossing
//!    of a face's interior, of an edge whose two faces lie on opposite sides of the segment's
//!    line, or of a mesh vertex is a root (t and its world point).  At a vertex x the line
//!    crosses iff the link of x, seen along the line, winds once around x (the two rays from x
//!    then start on opposite sides of Σ), decided by exact orientations.  A segment that meets
//!    an edge or a vertex and touches without crossing (both faces on the same side; a winding
//!    number of zero) is reported as an undecided region with reason singular_root at that
//!    point — the analogue of a double root, which the checks treat as a candidate witness.  A
//!    zero at t0 or t1 is boundary_root; a segment lying in a face's plane and meeting the face
//!    is non_isolated (and a vertex of that face on the segment stays singular_root).
//!  - surface_critical(d, domain): the mesh vertices in the domain that are strict local minima
//!    or maxima of the height ⟨x, d⟩ over their link (ties by index, above): every component has
//!    at least two (its highest and lowest vertices), which is what Lemma 5.2's seeds need.
//!  - surface_plane_contact(o, a, b, F): the mesh vertices exactly on the plane, inside F, where
//!    Σ ∩ Π is not a simple arc: the link's vertices, in cyclic order, do not change side exactly
//!    twice (a touching vertex: no change; a saddle: four or more) or one of them is also on
//!    the plane.  Under the perturbation there is no contact; these are the places where the
//!    unperturbed section is not a 1-manifold.
//!  - curve_critical(o, a, b, F): the section Σ ∩ Π is a set of polylines whose vertices are the
//!    crossings of mesh edges with Π; the roots are the polyline vertices inside F that are local
//!    extrema of ⟨x, a⟩ along their polyline, inside F up to the face-membership tolerance.
//!    The heights are compared exactly: those of the exact crossings of the mesh edges with the
//!    plane through o, o + a, o + b (interval arithmetic, exact rationals when the sign is not
//!    certain), and a tie counts as an extremum both ways.  FacetCycle
//!    then runs the paper's line test through them (facet_cycle.h): a closed polyline inside F
//!    has such a vertex, and the line through it in direction a meets the polyline twice.
//!  - silhouette_plane(o, a, b, d, F): the silhouette J_d is the set of mesh edges whose two faces
//!    face opposite ways relative to d (sign of ⟨n_f, d⟩, exact); the roots are its crossings with
//!    Π inside F.
//!  - silhouette_critical(d, d2, P): the vertices of J_d in the polytope P (world coordinates)
//!    that are local extrema of ⟨x, d2⟩ along J_d (both silhouette neighbours higher, or both
//!    lower), and those where J_d branches (four or more silhouette edges).
//! The other questions:
//!  - value_sign(x): −1 inside, +1 outside, 0 on Σ (exact): 0 if x lies on a face, else the
//!    parity of the crossings of Σ by one segment from x to a point q outside the bounding box of
//!    the vertices, with q perturbed symbolically to q + (ε, ε², ε³) so that the segment meets
//!    no edge or vertex and lies in no face's plane (no retried directions; time linear in the
//!    faces the segment meets);
//!    value_sign(lo, hi): the side of the box's centre if no face meets the box (exact
//!    do_intersect), else 0.
//!  - normal(x), gradient(x): n_x of the point of Σ closest to x: the face's unit outward normal
//!    inside a face; on an edge the normalised sum of its two faces' unit normals; at a vertex
//!    the angle-weighted mean of its faces' unit normals (normalised), unless some incident face
//!    does not face it (exact sign), in which case the plain mean of the face normals or the
//!    first incident face normal that every incident face faces, if one does: so that a sample at
//!    a vertex lies on the silhouette of its own normal only where no such direction was found.
//!    "On an edge / at a vertex"
//!    means within tolerances::mesh_feature_relative_distance of the box diagonal.
//!  - project(x): the closest point of Σ (AABB tree), if it lies in the box.
//!  - prove_gradient_cone(chart, P, w): a proof that ⟨n_f, w⟩ has one strict sign on every face
//!    that meets the bounding box of P (exact signs); then Σ ∩ P has no point where w is tangent,
//!    and no silhouette point for w.  It reports no refuting point.  gradient_sign(a, b, w): the common strict sign of ⟨n_f, w⟩
//!    over the faces the segment [a, b] meets (exact), so that the segment crosses Σ at most once
//!    and only one way; 0 if the signs differ or one is 0; +1 if no face meets it (vacuous).
//!  - solve(name, …): the six primitives above by their registry names and parameters; any other
//!    name is InvalidInput.
//!
//! What the guarantee rests on.  The Topological Ball Property (Edelsbrunner–Shah; Theorem 2.1 of
//! the paper) holds for any closed 2-manifold, PL included, and each check's answer above is
//! exact in its signs.  The paper's lemmas that turn "no witness" into the TBP (Lemma 5.3 and the
//! checks' lemmas) are proved for C² surfaces with Morse heights; their PL analogues (PL Morse
//! theory of generic heights on a triangulated surface) are what this oracle implements, but the
//! spacing bound of Lemma 5.1 fails at creases and cone vertices: there, termination rests on
//! the floor of DelMeshOptions::min_spacing, and a run that reaches it is uncertified.
//!
//! Threads: every query is const on the mesh and the prebuilt AABB tree; statistics are kept
//! under a lock, so the primitives may be called from several threads at once.

#include <chrono>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "meshing/core/surface_mesh.h"
#include "meshing/core/surface_oracle.h"
#include "meshing/inputs/sharp_features.h"

namespace delmesh {

class MeshOracle final : public SurfaceOracle {
 public:
  //! Builds the AABB tree of `mesh` (copied).  Preconditions (PreconditionViolation otherwise):
  //! mesh is a non-empty closed triangle mesh; every vertex lies strictly inside `box`.  The
  //! caller guarantees the rest of the file comment's assumptions (validate_input_mesh).
  //! The oracle works at unit scale (meshing/inputs/unit_scale.h): with k = unit_scale_exponent(box)
  //! (0 unless the box's largest side is below 2^-32 or at least 2^32), its surface, box(),
  //! clip_box() and every point, direction and domain of its questions and answers are the
  //! input's times 2^-k — exactly the same surface, scaled.  A run on it takes its lengths
  //! through unit_scale_options(…, k) and gives its results back through restore_scale(…, k)
  //! (meshing/driver/scaled_run.h).
  MeshOracle(const SurfaceMesh& mesh, const Box3& box);
  //! The k above: the oracle's coordinates are the input's times 2^-k.
  int scale_exponent() const { return scale_exponent_; }
  ~MeshOracle() override;

  //! Nothing to set: the oracle makes no random choice (ties are broken by index), and each
  //! primitive takes time linear in the faces near its domain, so it does not read the deadline
  //! (the refinement driver reads it between checks).
  void set_run_controls(std::uint64_t seed, std::optional<std::chrono::steady_clock::time_point> deadline) override;
  const Box3& box() const override { return box_; }
  //! The bounding box of the mesh's vertices (it holds every triangle), widened by
  //! tolerances::surface_box_relative_margin · diagonal() and met with B.
  const Box3& clip_box() const override { return clip_box_; }

  SolveResult surface_line(const Vec3& p, const Vec3& v, double t0, double t1) override;
  SolveResult surface_critical(const Vec3& d, const Domain& domain, std::size_t box_budget) override;
  SolveResult surface_plane_contact(const Vec3& o, const Vec3& a, const Vec3& b, const Domain& domain) override;
  SolveResult curve_critical(const Vec3& o, const Vec3& a, const Vec3& b, const Domain& domain) override;
  SolveResult silhouette_plane(const Vec3& o, const Vec3& a, const Vec3& b, const Vec3& d,
                               const Domain& domain) override;
  SolveResult silhouette_critical(const Vec3& d, const Vec3& d2, const Domain& domain) override;
  SolveResult solve(const std::string& primitive, const std::vector<double>& parameters, const Domain& domain,
                    std::size_t box_budget) override;

  ConeAnswer prove_gradient_cone(const AffineChart& chart, const Domain& domain, const Vec3& w) override;
  int gradient_sign(const Vec3& a, const Vec3& b, const Vec3& w) const override;
  using SurfaceOracle::value_sign;
  int value_sign(const Vec3& lo, const Vec3& hi) const override;

  Vec3 gradient(const Vec3& x) const override { return normal(x); }
  Vec3 normal(const Vec3& x) const override;
  std::optional<Vec3> project(const Vec3& x) const override;

  //! The feature edges (at the oracle's scale) whose Voronoi facets the Smooth check exempts
  //! (meshing/checks/smooth.h); none unless set.  The run sets them from its feature angle.
  void set_feature_edges(FeatureEdges edges) { feature_edges_ = std::move(edges); }
  const FeatureEdges& feature_edges() const { return feature_edges_; }

  //! A polyline of a plane section; closed: its last point joins its first.
  struct Polyline {
    std::vector<Vec3> points;
    bool closed = false;
  };
  //! The section of the whole mesh by the plane through o, o + a, o + b (a, b orthonormal), under
  //! the file comment's perturbation: closed polylines whose points are the crossings of mesh
  //! edges with the plane, in order along the section.  curve_critical() works on the same
  //! polylines restricted to the faces near its facet.
  std::vector<Polyline> section(const Vec3& o, const Vec3& a, const Vec3& b) const;

  //! {systems, certified_roots, undecided, seconds, backend: "mesh", faces, per_primitive:
  //!  {name: {calls, certified_roots, undecided, seconds}}, cone_certificates: {attempts, proved}}
  nlohmann::json statistics_json() const override;

 private:
  struct Impl;
  //! Counts one call of primitive `index` (its result, its start time).
  SolveResult finish(int index, SolveResult result, std::chrono::steady_clock::time_point start);

  std::unique_ptr<Impl> impl_;
  Box3 box_;
  Box3 clip_box_;
  struct Counts {
    std::size_t calls = 0, certified_roots = 0, undecided = 0;
    double seconds = 0;
  };
  std::vector<Counts> stats_;
  std::size_t cone_attempts_ = 0, cone_proved_ = 0;
  int scale_exponent_ = 0;
  FeatureEdges feature_edges_;
  mutable std::mutex statistics_mutex_;
};

}  // namespace delmesh
