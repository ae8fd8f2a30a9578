#pragma once
//! \file restricted_delaunay.h
//! Tri S|Σ (§5.1): the Delaunay triangles whose dual Voronoi edge meets Σ, where a zero of E at a
//! Voronoi vertex v of the edge uv counts only as the paper's perturbation Σ′ says: if
//! ⟨u − v, n_v⟩ > 0 and uv meets Σ nowhere else, the triangle is excluded; otherwise it is kept.
//!
//! The intersections of every Voronoi edge with Σ are computed once (SurfaceLine on the clipped
//! edge) and cached per Delaunay triangle (an open-addressing table keyed by sorted vertex ids,
//! meshing/core/detail/flat_table.h) until the triangle's dual edge changes.  Facet geometry (Voronoi facets with their seeded generic
//! frames) is cached per Delaunay edge in the same way.  The driver reports every change:
//! forget() and invalidate() drop records, shrink() marks the records of an insertion's cavity
//! boundary.
//!
//! Shrunk edges (update by restriction).  After an insertion the dual edge e′ of a cavity-boundary
//! triangle lies on the same line as its old edge e and e′ ⊆ e.  The record of e holds, for every
//! crossing and candidate, the parameter interval the solver enclosed it in; the roots of E on e′
//! are exactly the roots on e that lie in e′.  So when every enclosure lies either outside e′ or
//! inside e′ at distance more than the Voronoi-vertex tolerance from its ends (and the old record
//! has no unresolved region), the new record is the old one restricted to e′, with no solve.  Any
//! enclosure near an end of e′ (a zero at a new Voronoi vertex, the §5.1 case) makes the record be
//! solved again.  A record whose valid edge meets Σ nowhere (no crossing, candidate or unresolved
//! region) is kept as it is when E has a proved sign on the connectors of e′ (see Connectors
//! below; the one to the new Voronoi vertex is new): e′ ⊆ e misses Σ too, and such a record never
//! reads its edge again.  Otherwise it is solved again.
//!
//! Zeros at Voronoi vertices.  A zero of E that the isolator reports next to a Voronoi vertex v
//! of the edge (a certified root within tolerances::duplicate_sample_relative_distance of v, or
//! an undecided boundary_root region at v) is settled by interval proofs on the part R of its
//! range that lies in e, from v to the range's far end (solvers/gradient_cone.h):
//!  - if ⟨∇E, u − v⟩ has a proved sign s on R, E is strictly monotone there and R holds at most
//!    one zero.  Then if E(v) = 0 up to the rounding of its evaluation, the zero is v and the rule
//!    above decides with the proved sign s (not a floating-point dot product); if E(v) ≠ 0 is
//!    proved, R's zero, if E changes sign on R, is an ordinary crossing inside e, located by
//!    bisection on proved signs, and no zero lies in R otherwise.
//!  - if no sign is proved, R may hold several zeros: the zero is kept as a crossing at v and the
//!    record lists v as unresolved (the run cannot end complete while the edge is in Vor S).
//! Decisions are thus exact relative to the floating-point Voronoi vertex v.
//!
//! Connectors.  The edge the other faces see is the polyline v0, at(t0), at(t1), v1: its ends at
//! Voronoi vertices are the shared points v_i of voronoi_edge_ends(), which lie off e's line by
//! the circumcentres' errors (for a sliver, many times the membership margin), and SurfaceLine
//! searches only the segment of the line.  So E having one sign on a box holding the segment
//! proves the polyline misses Σ only together with the same proved sign on each connector
//! [v_i, at(t_i)] (its bounding box) not inside that box — tried first as one sign on the box
//! holding the segment and the v_i —; otherwise the edge is solved.  After a
//! solve, a connector not settled as a zero next to its vertex and without a proved sign is
//! settled alone: if E(v_i) = 0 up to rounding, as a zero at the vertex (above, with R the
//! connector); with E strictly monotone along it (a proved sign of ⟨∇E, at(t_i) − v_i⟩) and
//! E(v_i), E(at(t_i)) proved non-zero, it holds a crossing (reported at at(t_i)) iff they differ
//! in sign; otherwise the record has a crossing at v_i, unresolved.  The parity of a record's
//! crossings is thus the change of sign of E between its shared ends.  Any other undecided
//! region on the edge (a tangency, Lemma 4.7(ii), or an exhausted budget) is projected onto Σ
//! and kept as a candidate witness for VorEdge, or listed as unresolved if that fails.
//! A degenerate edge (VoronoiEdge::degenerate, numerically a point) is unresolved unless
//! SurfaceLine excludes Σ from a segment of length 2·duplicate_sample_relative_distance·diag
//! about it.

#include <array>
#include <functional>
#include <memory>
#include <optional>
#include <vector>

#include "common/seeded_uniform.h"
#include "meshing/core/detail/flat_table.h"
#include "meshing/core/detail/parallel_for.h"
#include "meshing/core/surface_oracle.h"
#include "meshing/voronoi/delaunay.h"
#include "meshing/voronoi/voronoi_geometry.h"

namespace delmesh {

//! A read-only run of points held by a VoronoiEdgeRecord (valid while the record lives unchanged).
class RecordPoints {
 public:
  RecordPoints() = default;
  RecordPoints(const Vec3* first, std::size_t count) : first_(first), count_(count) {}
  const Vec3* begin() const { return first_; }
  const Vec3* end() const { return first_ + count_; }
  std::size_t size() const { return count_; }
  bool empty() const { return count_ == 0; }
  const Vec3& front() const { return first_[0]; }
  const Vec3& operator[](std::size_t i) const { return first_[i]; }

 private:
  const Vec3* first_ = nullptr;
  std::size_t count_ = 0;
};

//! The lists of a VoronoiEdgeRecord while they are built (RestrictedDelaunay::compute()).
struct VoronoiEdgeLists {
  std::vector<Vec3> unresolved, crossings, candidates;
  //! [t_lo, t_hi] of each crossing and each candidate.
  std::vector<std::array<double, 2>> crossing_range, candidate_range;
  //! Empties every list (keeping the capacity).
  void clear();
};

//! The Voronoi edge of one Delaunay triangle and its intersections with Σ.  The record keeps the
//! edge's extent on its line (t0, t1 and the kinds of its ends), not the line: that is
//! voronoi_edge_line() of the triangle, a function of the triangle's points, which never change,
//! rebuilt by edge().  The lists live in one block of their own, allocated only when one of them
//! is not empty (most edges miss Σ), so that the records of a large triangulation stay small:
//! 32 bytes each, one per Delaunay triangle.
class VoronoiEdgeRecord {
 private:
  // The extent of the edge (VoronoiEdge's members of the same names).
  double t0_ = 0, t1_ = 0;
  //! Block layout: one entry holding the three counts (of unresolved, crossings, candidates),
  //! then the points of the five lists in the order of list().
  std::unique_ptr<Vec3[]> lists_;
  bool at_vertex0_ = false, at_vertex1_ = false, valid_ = false, degenerate_ = false;

 public:
  bool restricted = false;  //!< the triangle is in Tri S|Σ (with the §5.1 rule)
  bool shrunk = false;      //!< the dual edge shrank since: restrict or solve again on use
  //! E has a proved sign on a box holding the edge's segment and its connectors (compute()'s
  //! first step), so on every subset of that box.
  bool segment_signed = false;

  VoronoiEdgeRecord() = default;
  VoronoiEdgeRecord(const VoronoiEdgeRecord& other)
      : t0_(other.t0_),
        t1_(other.t1_),
        lists_(copy(other)),
        at_vertex0_(other.at_vertex0_),
        at_vertex1_(other.at_vertex1_),
        valid_(other.valid_),
        degenerate_(other.degenerate_),
        restricted(other.restricted),
        shrunk(other.shrunk),
        segment_signed(other.segment_signed) {}
  VoronoiEdgeRecord& operator=(const VoronoiEdgeRecord& other);
  VoronoiEdgeRecord(VoronoiEdgeRecord&&) noexcept = default;
  VoronoiEdgeRecord& operator=(VoronoiEdgeRecord&&) noexcept = default;

  //! The recorded Voronoi edge, given the triangle t it belongs to and the triangulation `del`
  //! that holds t's points: voronoi_edge_line(del, t) with the recorded extent.
  VoronoiEdge edge(const Delaunay& del, const TriangleKey& t) const;
  //! Records the extent of e (an edge of voronoi_edge() or its restriction, on its triangle's
  //! line); the line itself is not kept.
  void set_edge(const VoronoiEdge& e);
  //! VoronoiEdge::valid and VoronoiEdge::degenerate of the recorded edge.
  bool edge_valid() const { return valid_; }
  bool edge_degenerate() const { return degenerate_; }

  //! Centres of the undecided regions on e that are neither a zero at a Voronoi vertex nor a
  //! candidate (projection failed or left the edge), and the point of a degenerate edge that Σ
  //! may pass through: what the record could not settle.
  RecordPoints unresolved() const { return list(0); }
  //! All points of e ∩ Σ (certified, and zeros at Voronoi vertices).
  RecordPoints crossings() const { return list(1); }
  //! Projected undecided regions (tangency candidates).
  RecordPoints candidates() const { return list(2); }
  //! The counted point of e ∩ Σ of a restricted triangle, its first crossing (the origin when
  //! the triangle is not restricted).
  Vec3 dual_point() const { return restricted ? crossings().front() : Vec3{}; }
  //! The solver's enclosure [t_lo, t_hi] on the edge's line of each crossing and each candidate,
  //! as the first two coordinates of each entry (the third is 0).
  RecordPoints crossing_range() const { return list(3); }
  RecordPoints candidate_range() const { return list(4); }
  //! Replaces the lists by these.  Throws PreconditionViolation unless each range list is as long
  //! as its point list.
  void set_lists(const VoronoiEdgeLists& lists);

 private:
  RecordPoints list(int which) const;
  static std::unique_ptr<Vec3[]> copy(const VoronoiEdgeRecord& other);
};

class RestrictedDelaunay {
 public:
  RestrictedDelaunay(const Delaunay& del, SurfaceOracle& oracle, std::uint64_t seed);

  //! The record of a current Delaunay triangle (computed on first use, then cached).  `apexes`,
  //! if given, are Delaunay::triangle_apexes(t) (saves looking them up).
  const VoronoiEdgeRecord& voronoi_edge_record(const TriangleKey& t, const std::array<VertexId, 2>* apexes = nullptr);
  //! The cached record of t as it stands (possibly marked shrunk), or nullptr; computes nothing.
  //! Invariant: while every change of Del S is reported (shrink(), forget() before a removal),
  //! records and facets are cached only for current Delaunay triangles and edges.
  const VoronoiEdgeRecord* cached_record(const TriangleKey& t) const;
  //! Drops the cached geometry of the facet of e (it is rebuilt if asked for again): the driver
  //! calls it once the facet checks of e are done, so that memory stays proportional to the
  //! facets in work, not to all of Vor S.
  void release_facet(const EdgeKey& e) { facets_.erase(e); }
  //! For a local insertion (Delaunay::insert's change): forgets the destroyed triangles' records,
  //! the destroyed edges' facets and the shrunk ones' geometry (shrink_facets()), like shrink()
  //! without marking the shrunk triangles (prepare_star() takes them up next).  Returns the destroyed triangles that were
  //! restricted or had no up-to-date record: the restricted stars of their vertices may change.
  std::vector<TriangleKey> forget_destroyed(const InsertionChange& change);
  //! A triangle of prepare_star(): its record now, and what its record said before.
  struct StarRecord {
    const VoronoiEdgeRecord* record = nullptr;
    bool had_record = false;      //!< an up-to-date record existed before
    bool was_restricted = false;  //!< … and it was restricted
    Vec3 old_dual_point{};        //!< … with this dual point
    //! The record was solved afresh (not restricted from the old one): a new solver answer, which
    //! may hold what the old one did not (a tangency candidate, two crossings at the new vertex),
    //! so its VorEdge check must run as on a new face.
    bool solved = false;
  };
  //! After forget_destroyed(): brings the records of the new vertex's closed star up to date —
  //! link triangles (not containing the vertex) are shrunk and restricted from their records
  //! where possible, the others solved on `parallel`'s threads — and returns them in the star's
  //! order.  The result does not depend on the number of threads; the pointers stay valid until
  //! the records are forgotten.
  std::vector<StarRecord> prepare_star(const std::vector<Delaunay::StarTriangle>& star,
                                       const detail::ParallelFor& parallel);
  //! Enters the facets of new Delaunay edges, empty: their geometry (facet()) and their section
  //! certificates (facet_section_certified()) are computed when a check first asks for them, on
  //! the Del S of that moment.  An edge that a later insertion destroys before its checks run
  //! then costs nothing, and one it shrinks is certified on its smaller facet, where the cell
  //! certificates made in between may already certify it.  (A facet's certificate holds on
  //! every subset of the facet, so computing it later certifies the same facets or more.)
  void add_facets(const std::vector<EdgeKey>& edges);
  //! Whether Σ misses the facet F of the Delaunay edge e = pq, proved from `ring`, the triangles
  //! pqr (as Delaunay::edge_ring(e), in any order, with their apexes), and `boundary`, their
  //! current records: boundary[i] the record of pq·ring[i].third (throws PreconditionViolation
  //! if the two differ in length).  F ∩ B is a convex polygon
  //! (F = Π ∩ ⋂_r {|x − p| ≤ |x − r|}, Π the bisector plane of pq: each edge of F is the Voronoi
  //! edge of one pqr), so it lies in the bounding box of its vertices, which are of three
  //! kinds: (1) Voronoi vertices of F in B and (2) points where an edge of F leaves B — together
  //! the ends of the valid Voronoi edges of F —, and, only when F reaches ∂B, (3) points where the
  //! relative interior of F meets an edge of B: the points of Π ∩ (edges of B) on p's side of every
  //! bisector of p and r, each taken if it violates none by more than the margin
  //! M = tolerances::face_membership_relative_tolerance·diag (rounding can add points, never lose
  //! one).  The computed ends at(t) of the edges stand for those vertices: an exact Voronoi vertex
  //! v* of F lies within δ(v) = dist(v, box of the ends) + ρ(v) of that box, v its computed
  //! point (voronoi_vertex(), the point F's cuts hold) and ρ(v) its certified error radius
  //! (certified_voronoi_vertex(); the records' edges may be older and longer than the current
  //! ones, which only makes the box larger); vertices farther than ρ(v) outside the clip box are
  //! not vertices of F ∩ B.  So the box enlarged by max(M, 2δ), δ the largest δ(v) (twice, for
  //! the rounding of δ and of the enlargement), holds F when every edge of F ends at Voronoi
  //! vertices.  The points of the kinds (2) and (3) rest on the rounding of the edges' lines
  //! and of Π (the circumcentres of the triangles and their normals, not certified), which M
  //! covers; when F reaches ∂B and 2δ > M no proof is attempted (false).  E keeping one sign on
  //! the enlarged box, proved by interval arithmetic on at most tolerances::facet_miss_box_budget
  //! sub-boxes, proves F ∩ Σ = ∅.  False proves nothing; it is returned at once when a Voronoi
  //! edge of F meets Σ (crossings, candidates or unresolved regions: then F ∩ Σ ≠ ∅ or undecided)
  //! or is degenerate.  Counted (facets_missing_surface()).
  bool facet_misses_surface(const EdgeKey& e, const std::vector<Delaunay::RingTriangle>& ring,
                            const std::vector<const VoronoiEdgeRecord*>& boundary);
  //! Whether the facet of e is cached, its geometry or only its section certificate (then e is
  //! a current Delaunay edge).
  bool has_facet(const EdgeKey& e) const { return facets_.find(e) != nullptr; }
  //! The facet of a current Delaunay edge (computed on first use, then cached).  `ring`, if
  //! given, is Delaunay::edge_ring(e) in any order (saves looking it up).
  const VoronoiFacet& facet(const EdgeKey& e, const std::vector<Delaunay::RingTriangle>* ring = nullptr);
  //! Whether Σ ∩ F is proved to be a regular curve with no critical point in some in-plane
  //! direction (solvers/gradient_cone.h, with w the in-plane part of ∇E at the midpoint of pq): then
  //! FacetContact and FacetCycle have no witness in F.  For a degenerate facet (no area in
  //! doubles) the cone is tried on VoronoiFacet::polygon_hull() widened by
  //! face_membership_relative_tolerance · diag, which holds F.  Computed once per facet.
  //!
  //! The facet's own cover is not needed when the cell of p or of q is certified with a slope
  //! (cell_certified()): F ⊆ V_p ∩ V_q, so a proof |⟨∇E, n_p⟩| ≥ ρ |∇E| on Σ ∩ V_p with
  //! |⟨n_p, q − p⟩| / |q − p| < ρ (bounded by interval arithmetic; q − p is normal to F's plane)
  //! is the certificate of F with the in-plane direction n_p − ⟨n_p, q − p⟩ (q − p) / |q − p|²
  //! (the slope argument of solvers/gradient_cone.h).  Nor when the proof over V_p (with or
  //! without a slope) came with a box holding Σ ∩ V_p (SurfaceOracle::ConeAnswer::surface_box)
  //! that the plane of F, the bisector of p and q, misses (one interval evaluation over the box):
  //! then Σ ∩ F ⊆ Σ ∩ V_p lies off F's plane, so Σ ∩ F = ∅ and FacetContact and FacetCycle have
  //! nothing to look at.  Nor when both V_p and V_q are certified with a sign, whatever their
  //! slopes: u = σ_p n_p and v = σ_q n_q with ⟨∇E, u⟩ > 0 on Σ ∩ V_p and ⟨∇E, v⟩ > 0 on Σ ∩ V_q
  //! (CellCertificate::orientation), and with M = q − p, ⟨M, u⟩ and ⟨M, v⟩ proved non-zero and of
  //! opposite signs (interval arithmetic).  Then w′ = |⟨M, v⟩| u + |⟨M, u⟩| v is parallel to F's
  //! plane (⟨w′, M⟩ = 0 by the opposite signs) and, at every x ∈ Σ ∩ F ⊆ Σ ∩ V_p ∩ V_q,
  //! ⟨∇E(x), w′⟩ > 0 as a sum of two positive terms: the certificate of F with
  //! the in-plane direction w′.  (On a smooth surface the normals at the ends of a short chord
  //! tilt to opposite sides of it, so this holds for most facets across Σ, where the slope needs
  //! |⟨n_p, M⟩| / |M| below ρ_p and that can exceed any slope a cover proves.)  V_p only shrinks
  //! while the proof is kept, so the three routes hold for the facets of the current V_p.  They
  //! rest on what the cell's proof rests on: that the cell's domain holds the exact V_p ∩ B, so
  //! that the exact F ⊆ V_p ∩ V_q lies in it.  Its half-spaces are the exact bisectors moved
  //! outwards (up to the rounding of one dot product), and its box, when built from the Voronoi
  //! vertices, is their bounding box enlarged by the membership margin or twice their largest
  //! certified error radius if larger (voronoi_geometry.h), so it holds the exact vertices; the
  //! computed F (whose cuts hold the computed vertices) need not lie in it, and is not what the
  //! routes certify.  Counted
  //! (facets_certified_by_cell()).  This route reads no geometry of F, and holds whether F ∩ B is
  //! a polygon, degenerate or empty; it is tried first, and a facet it certifies is not built
  //! until facet() is asked for it.
  bool facet_section_certified(const EdgeKey& e);
  //! The Silhouette certificate of V_p (silhouette.h): the gradient cone with w = n_p =
  //! ∇E(p)/|∇E(p)| over voronoi_cell(p), its slope kept.  A proof is kept until V_p may have grown
  //! (invalidate() or forget_cell() of p, a non-local shrink()): insertions only shrink V_p, and a
  //! proof over V_p holds on every subset of it.  A failure is kept while Del S has as many
  //! vertices (it is not tried again on the same cell).  Returns whether a proof is kept now.
  //! `facet_sites`: the q whose facets pq are to be certified from the cell; the cover is refined
  //! (SlopeRefinement) towards the least slope that certifies those of them with
  //! |⟨n_p, q − p⟩| / |q − p| ≤ tolerances::cell_slope_cap, within
  //! tolerances::cell_slope_box_budget extra boxes.  Facets that q's kept certificate already
  //! certifies (facet_section_certified()'s routes through the cells), or would with a proof of
  //! ⟨∇E, n_p⟩ > 0 over V_p (the sign of the two-cell route), do not raise that slope; when they
  //! are all the facets, V_p is proved without a slope (for the sign).  When the oracle bounds
  //! no slopes, nothing is tried with facet sites (Silhouette's turn, as without facets).
  bool cell_certified(VertexId p, const std::vector<VertexId>& facet_sites = {});
  //! cell_certified(x, neighbours) for a vertex x just inserted: the facets of every new edge xq
  //! are the facet sites, and V_x is built from x's Delaunay cells `cells` and neighbours
  //! `neighbours` (Delaunay::incident_cells(x) and Delaunay::neighbours(x), taken by the caller;
  //! voronoi_cell()'s second form).  It reads the points of Del S, the cell certificates of the
  //! neighbours and the oracle, and writes only the table of cell certificates (x's, growing the
  //! table to hold it), so it may run on one thread while prepare_star() of x's star runs on
  //! another (which reads and writes none of these but the points and the oracle, both read-only
  //! and thread-safe).
  bool certify_new_cell(VertexId x, const std::vector<std::array<VertexId, 4>>& cells,
                        const std::vector<VertexId>& neighbours);
  //! When the kept certificate of V_p (cell_certified() without facet sites) failed because it
  //! proved a point of Σ ∩ V_p where ⟨∇E, n_p⟩ = 0 — a point of the silhouette J_{n_p} in V_p
  //! (SurfaceOracle::ConeAnswer::vanishing_point) — that point; nothing otherwise, or once Del S
  //! has changed since.
  std::optional<Vec3> cell_silhouette_point(VertexId p) const;
  //! Forgets the cell certificate of p (before p is removed, or when V_p may grow).
  void forget_cell(VertexId p);
  //! The seeded rotation of the frame of facet e (generic in-plane direction d = a); attempt k > 0
  //! gives the k-th alternative rotation (attempt_seed()).
  double facet_rotation(const EdgeKey& e, int attempt = 0) const;
  //! The facet of a current Delaunay edge e in the frame of rotation facet_rotation(e, attempt),
  //! built anew (not cached): the same polygon and domain as facet(e) in another frame.
  VoronoiFacet rotated_facet(const EdgeKey& e, int attempt) const;

  //! Forgets the cached record of every current Delaunay triangle and edge all of whose vertices
  //! are in `vertices` (sorted ascending), and the cell certificates of those vertices, except
  //! that, given `grown_into` (a domain that holds every part of Vor S the cells of `vertices`
  //! may have grown into: the cell of a removed vertex, taken before its removal), a proved cell
  //! certificate is kept with that domain added to its grown parts: cell_certified() then has
  //! only to prove the cone on the cell's part inside each grown part.  Why that suffices: when a
  //! site s is removed, a point y of the new V_p outside the old V_s is closer to some remaining
  //! site than to s, and closest to p among the sites other than s, hence closest to p among all
  //! of them: y is in the old V_p.  So V_p ⊆ (old V_p) ∪ (V_p ∩ old V_s), and, by induction over
  //! removals and the insertions between them (which only shrink V_p), V_p lies in the cell of
  //! the proof together with its grown parts.
  void invalidate(const std::vector<VertexId>& vertices, const Domain* grown_into = nullptr);
  //! Forgets the records of these simplices (e.g. the star of a vertex about to be removed).
  void forget(const std::vector<TriangleKey>& triangles, const std::vector<EdgeKey>& edges);
  //! Applies an insertion's change: destroyed simplices are forgotten, shrunk facets keep only a
  //! proved section certificate, shrunk edge records are kept for restriction.  A non-local
  //! change forgets everything.
  void shrink(const InsertionChange& change);
  //! Number of edge records solved, and of those obtained by restriction (statistics).
  std::size_t records_solved() const { return records_solved_; }
  std::size_t records_restricted() const { return records_restricted_; }
  //! Facets built, and facets proved to miss Σ without being built (statistics).
  std::size_t facets_built() const { return facets_built_; }
  std::size_t facets_missing_surface() const { return facets_missing_surface_; }
  //! Facet certificates obtained from a certified cell (facet_section_certified()).
  std::size_t facets_certified_by_cell() const { return facets_certified_by_cell_; }

  //! Restricted triangles incident to p (current Delaunay triangles only), ascending.
  std::vector<TriangleKey> star(VertexId p);
  //! The same triangles in no particular order, without a copy when every current triangle has
  //! its record (the kept star of p); valid until the next call or the next change of Del S.
  const std::vector<TriangleKey>& star_unordered(VertexId p);
  //! The restricted triangles that contain the edge e, ascending, if there are exactly two (e is
  //! then an interior edge of the surface Tri S|Σ around it); nothing otherwise.  The same as
  //! filtering star(e[0]), without copying the star.
  std::optional<std::array<TriangleKey, 2>> restricted_pair(const EdgeKey& e);
  //! The caller promises that from now on every current Delaunay triangle has a record whenever
  //! star() is called (the refinement driver computes each new or changed triangle's record at
  //! once).  star() then reads the restricted stars kept up to date with the records instead of
  //! walking Del S.
  void assume_every_triangle_recorded() { every_triangle_recorded_ = true; }
  //! The number of cached records.  While the invariant of cached_record() holds and, after
  //! assume_every_triangle_recorded(), every current triangle has its record, it equals
  //! Delaunay::triangle_count().
  std::size_t record_count() const { return edges_.size(); }
  //! All of Tri S|Σ, ascending.  After assume_every_triangle_recorded(), read from the
  //! restricted stars (precondition: every record up to date, i.e. no insertion since the last
  //! prepare_star()); otherwise every Delaunay triangle's record is looked up or solved.
  std::vector<TriangleKey> triangles();

  const Delaunay& delaunay() const { return del_; }
  SurfaceOracle& oracle() { return oracle_; }
  std::uint64_t seed() const { return seed_; }
  //! The unresolved regions (VoronoiEdgeRecord::unresolved) of the current Delaunay triangles, by
  //! triangle, ascending.  Precondition: assume_every_triangle_recorded() and every record up to
  //! date (no insertion since the last prepare_star()).
  std::vector<std::pair<TriangleKey, Vec3>> unresolved_regions() const;
  //! Calls f(t, record) for the record of every current Delaunay triangle t, in no particular
  //! order.  Precondition: as for unresolved_regions().
  template <class F>
  void for_each_record(F&& f) const {
    edges_.for_each(std::forward<F>(f));
  }

 private:
  //! Solves the record of t: SurfaceLine on its dual edge, unless one interval evaluation of E on
  //! a box holding the edge proves E ≠ 0 there (then e ∩ Σ = ∅).  Touches no member: safe to
  //! call from several threads at once.
  VoronoiEdgeRecord compute(const TriangleKey& t, const std::array<VertexId, 2>* apexes) const;
  //! Whether E has a proved sign on the connector of the edge of t (apexes `apexes`, after the
  //! insertion of x) to its new Voronoi vertex (that of the cell t·x; both if x is not an apex),
  //! r being t's record, kept because its older edge missed Σ (the older vertex's connector was
  //! settled when r was computed): the connector [v, a], a the projection of v onto the edge's
  //! line, inside the box on which r's sign was proved (VoronoiEdgeRecord::segment_signed) or of
  //! a proved sign itself.
  bool kept_connectors_clean(const VoronoiEdgeRecord& r, const TriangleKey& t, const std::array<VertexId, 2>& apexes,
                             VertexId x) const;
  //! The record of t restricted from its shrunk one, or nothing with `current` set to the
  //! cached record if it is up to date (nullptr if none or if it must be solved).
  std::optional<VoronoiEdgeRecord> update_without_solving(const TriangleKey& t, const std::array<VertexId, 2>* apexes,
                                                          const VoronoiEdgeRecord*& current);
  using RecordTable = detail::FlatTable<3, VoronoiEdgeRecord>;
  //! Stores the record of t (counting it as solved or restricted) and keeps stars_ in step.
  const VoronoiEdgeRecord& install(const TriangleKey& t, VoronoiEdgeRecord&& record, bool solved);
  //! The same at a known slot whose previous record had restricted status `was_restricted`.
  const VoronoiEdgeRecord& assign(const TriangleKey& t, VoronoiEdgeRecord& slot, bool was_restricted,
                                  VoronoiEdgeRecord&& record, bool solved);
  //! cell_certified() with V_p from `cell`, called only when a proof is tried.
  bool certify_cell(VertexId p, const std::vector<VertexId>& facet_sites, const std::function<VoronoiCell()>& cell);
  //! How the section of a facet was certified, if it was.
  enum class SectionProof : signed char { none, by_cell, by_cover };
  //! The two certificates of facet_section_certified(), tried in this order; both are
  //! thread-safe while no cell certificate is being added.  From the certified cells of p and q
  //! (one of them, or both with signs): reads the cells and the sites only, not F's geometry (a
  //! proof over V_p holds on every part of it, F ∩ B empty or degenerate included).
  SectionProof certify_by_cell(const EdgeKey& e) const;
  //! The gradient cone over F (a valid or degenerate facet; none for an empty one).
  SectionProof certify_by_cover(const EdgeKey& e, const VoronoiFacet& f) const;
  //! Stores a facet's certificate and counts one obtained from a cell.
  void record_section(int& slot, SectionProof proof);
  //! Keeps stars_ in step with a record of t whose restricted status went from `was` to `is`.
  void track(const TriangleKey& t, bool was_restricted, bool is_restricted);
  void erase_record(const TriangleKey& t);
  //! The facets of edges whose facets shrank: the geometry is forgotten (rebuilt on demand), and
  //! so is a section certificate that failed or was not tried; a proved one is kept.  The
  //! shrunk facet F′ lies in F, in the same plane, and the in-plane direction of the proof
  //! depends on the edge's sites only, so the proof over F holds over F′ (the monotonicity lemma
  //! of refinement.h, with its conditions).
  void shrink_facets(const std::vector<EdgeKey>& edges);
  //! The record of t's shrunk edge `edge` restricted from t's record `old`, or nothing if it must
  //! be solved.
  std::optional<VoronoiEdgeRecord> restrict_record(const TriangleKey& t, const VoronoiEdgeRecord& old,
                                                   const VoronoiEdge& edge) const;

  const Delaunay& del_;
  SurfaceOracle& oracle_;
  std::uint64_t seed_;
  RecordTable edges_;
  //! A facet certified by a cell has no geometry until facet() is asked for it.
  struct FacetEntry {
    VoronoiFacet facet;
    bool built = false;          //!< `facet` holds F's geometry
    int section_certified = -1;  //!< −1 not tried, 0 failed, 1 proved
  };
  detail::FlatTable<2, FacetEntry> facets_;
  //! The entry of e, added empty (no geometry, no certificate) if there is none.
  FacetEntry& facet_entry(const EdgeKey& e);
  std::size_t records_solved_ = 0, records_restricted_ = 0;
  std::size_t facets_built_ = 0, facets_missing_surface_ = 0, facets_certified_by_cell_ = 0;
  //! cells_[p]: the kept cell certificate of p (cell_certified()).
  struct CellCertificate {
    enum class State : signed char { none, proved, failed } state = State::none;
    Vec3 w{};                   //!< n_p, the cone's direction
    double slope = 0;           //!< the proof's slope (0: none)
    //! σ = ±1 if the proof gives ⟨∇E, σ n_p⟩ > 0 on all of Σ ∩ V_p, 0 if it does not
    //! (SurfaceOracle::ConeAnswer::orientation).
    int orientation = 0;
    //! A box that holds Σ ∩ V_p, from the proof, if the oracle gives one
    //! (SurfaceOracle::ConeAnswer::surface_box).
    std::optional<std::array<Vec3, 2>> surface_box;
    //! Domains V_p may have grown into since its proof (invalidate()): while there are any, the
    //! proof covers only the rest of V_p, and nothing follows from it until they are proved.
    std::vector<Domain> grown;
    std::size_t vertices = 0;   //!< |S| when a failure was found
    std::optional<Vec3> silhouette_point;  //!< the point of J_{n_p} ∩ V_p that refuted it, if any
  };
  std::vector<CellCertificate> cells_;
  //! Completes the kept proof c of V_p (`cell`) on V_p's parts in c.grown, with the same cone
  //! direction c.w = n_p, towards the same slope when it has one (the least slope of the parts is the
  //! slope of the whole; the union of their boxes around Σ its box); true if every part is
  //! proved, and then c covers all of V_p.  A failure without a slope is kept as a failure on V_p
  //! (with the refuting point, if any); with a slope c is left as it was, for a proof anew.
  bool complete_grown_cell(CellCertificate& c, const VoronoiCell& cell);
  //! A certificate that covers all of the current V_p.
  static bool covers_cell(const CellCertificate& c) {
    return c.state == CellCertificate::State::proved && c.grown.empty();
  }
  //! The two-cell route of facet_section_certified() for the facet of pq, given u = σ_p n_p (the
  //! signed direction of a proof over V_p) and q's certificate cq: whether cq covers V_q with a
  //! sign and q − p is proved to have inner products of opposite signs with u and σ_q n_q.
  static bool signs_certify(const Vec3& p, const Vec3& q, const Vec3& u, const CellCertificate& cq);
  //! Whether c is a failure found on the current Del S (so it still stands).
  bool failure_kept(const CellCertificate& c) const {
    return c.state == CellCertificate::State::failed && c.vertices == del_.size();
  }
  //! stars_[v]: the recorded restricted triangles containing v (in no particular order).
  std::vector<std::vector<TriangleKey>> stars_;
  bool every_triangle_recorded_ = false;
};

}  // namespace delmesh
