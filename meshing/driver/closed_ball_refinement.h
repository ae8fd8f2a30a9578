#pragma once
//! \file closed_ball_refinement.h
//! Remeshing a triangle mesh Σ (a piecewise-linear surface): refinement by the closed-ball
//! property, and the rule by which such a run is `complete`.
//!
//! Refinement.  After each phase's Refinement::run() ends complete, refine_closed_ball() checks
//! the closed-ball property of the current samples S on Σ (meshing/checks/closed_ball.h, exact);
//! while it is violated, every violation's witness (a vertex of the offending face's restricted
//! polygons, a point of Σ) goes through Refinement::insert() — so the duplicate tolerance and the
//! termination floor apply and the changed faces are queued — then run() again, and the check
//! again.  It stops when the property holds, when it is non_generic, when every witness of a
//! round is refused, or when run() stops at a limit (time, points, interrupt).
//!
//! Theorem (Edelsbrunner and Shah 1997, Theorem 2.1; closed_ball.h).  If Vor S and Σ are in
//! general position and every Voronoi face meets Σ in nothing or a closed ball, then Del S|Σ is
//! homeomorphic to Σ.
//!
//! The status rule for a PL input (decide_pl_status).  The run's output Tri S|Σ is homeomorphic
//! to Σ when both of these hold on the final S:
//!  (a) closed_ball_check(S, Σ) reports `holds` — general position and the closed-ball property,
//!      decided exactly from the labels of Vor S|Σ (restricted_voronoi_mesh.h; no rounded value is
//!      read);
//!  (b) the triangles of Tri S|Σ (what the refinement computed, the output's faces) are, as sets
//!      of sample triples, exactly Del S|Σ of the exact check.
//! (a) gives the theorem's hypothesis, the theorem gives Del S|Σ ≅ Σ, and (b) transfers it to the
//! output.  The smooth-surface topology rows — VorEdge, FacetContact, TopoDisk, FacetCycle,
//! Silhouette and the seed findings — stand in for the topological ball property of a C² surface
//! (Theorem 5.1 of the paper); on a PL surface their findings (mostly at creases and corners,
//! where their smoothness premises fail) are then not needed for the claim and do not block
//! `complete`: they are counted as exempt with the reason, never dropped.
//! Geometry findings keep blocking (Quality, size, distance, a registered geometry row, and the
//! floor on them), except a Smooth finding on a crease edge: an edge pq of Tri S|Σ whose
//! Voronoi facet V_p ∩ V_q meets a feature edge of Σ at the run's feature angle
//! (smooth_exempt_edge, meshing/checks/smooth.h; decided exactly: an edge cut of B(p, q) on a
//! feature edge lies in the closed cell V_p, i.e. is a vertex of the facet's curve in Vor S|Σ):
//! the roughness bound 2β(λ) rests on Σ being C² near pq and cannot hold across a crease.  The
//! refinement does not refine such an edge (the Smooth check reports it unsettled instead of
//! inserting a witness), so without (a) and (b) the run cannot end complete.  The edge of a
//! Smooth finding is found exactly: the finding's location is smooth_witness()'s point,
//! recomputed on the final Tri S|Σ for every edge; the finding is exempt when every edge giving
//! that point is a crease edge.  With features off (--no-features) no edge is a crease edge.
//! Everything else of the old rule stays: the run must have ended complete (every queue empty),
//! the output must have no defect (closed, manifold, consistently oriented), the solver's answers
//! certified.  When (a) or (b) fails — violated, non_generic, or Tri S|Σ ≠ Del S|Σ — nothing is
//! exempt and the status is Refinement::certify()'s.

#include <cstddef>
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "meshing/checks/closed_ball.h"
#include "meshing/core/mesh_status.h"
#include "meshing/core/surface_mesh.h"
#include "meshing/driver/refinement.h"

namespace delmesh {

//! The closed-ball refinement of one run, over its phases.
struct ClosedBallRefinement {
  std::size_t rounds = 0;               //!< checks that reported violations and led to insertions
  std::size_t checks = 0;               //!< closed-ball checks run
  std::size_t witnesses_inserted = 0;
  std::size_t witnesses_rejected = 0;   //!< refused by the duplicate tolerance or the floor
  ClosedBallResult last;                //!< the latest check
  bool last_is_current = false;         //!< no sample was inserted since `last`
  std::vector<VertexId> sample_ids;     //!< last's sample index → Delaunay vertex id
  double seconds = 0;
};

//! The loop of the file comment, on the samples of `refinement` and Σ = `sigma` (at the oracle's
//! scale).  `status` is what the phase's run() returned; the loop runs only if it is complete, and
//! returns the status of the last run().  Precondition: sigma is a closed triangle mesh without
//! removed elements.
MeshStatus refine_closed_ball(Refinement& refinement, const SurfaceMesh& sigma, MeshStatus status,
                              ClosedBallRefinement& record);

//! A Voronoi vertex this close to Σ, relative to its circumradius, is "at Σ" for the mismatch
//! classification (a few hundred units in the last place of the coordinates of a unit-scale run).
inline constexpr double mismatch_vertex_relative_distance = 1e-12;

//! The outcome of the status rule of the file comment.
struct PlStatusDecision {
  MeshStatus status = MeshStatus::uncertified;
  //! record.last was computed on the final samples (else nothing below is decided)
  bool check_current = false;
  bool proves_homeomorphism = false;         //!< (a) and (b)
  bool output_equals_restricted_delaunay = false;
  std::size_t only_restricted_delaunay = 0;  //!< triples of Del S|Σ not in Tri S|Σ
  std::size_t only_output = 0;               //!< triangles of Tri S|Σ not in Del S|Σ
  //! The triangles in one set and not the other, by where they differ (classify_mismatch):
  //! at_voronoi_vertex — one of the triangle's Delaunay cells has its Voronoi vertex (the mesher's
  //! computed one, voronoi_vertex()) within mismatch_vertex_relative_distance times its
  //! circumradius of Σ: the mesher decided that Voronoi edge's crossing with its rounded vertex
  //! and the §5.1 rule (restricted_delaunay.h), the exact check with the exact vertex, so the two
  //! conventions for a zero at a Voronoi vertex differ there; not_delaunay — a triangle of Tri S|Σ
  //! that is not a triangle of Del S (a stale record); elsewhere — any other.
  std::size_t mismatch_at_voronoi_vertex = 0, mismatch_not_delaunay = 0, mismatch_elsewhere = 0;
  //! Exempt findings: check kind name → reason → count; and the findings still blocking.
  std::map<std::string, std::map<std::string, std::size_t>> exempt;
  std::size_t exempt_count = 0;
  std::size_t blocking = 0;
};

//! Decides the status of a PL run (file comment).  `run_status` is the last run()'s,
//! `certification` Refinement::certify()'s, `output_defective` and `solver_certified` as in
//! del_mesh; `lambda` the run's λ (Smooth's threshold 2β(λ)), `geometry` whether the geometry rows
//! ran.  Unless record.last was computed on the final samples (the Delaunay vertices are still
//! record.sample_ids), nothing is exempt and the status is certification.status's.
PlStatusDecision decide_pl_status(Refinement& refinement, const ClosedBallRefinement& record, MeshStatus run_status,
                                  const Certification& certification, bool output_defective,
                                  bool solver_certified, double lambda, bool geometry);

//! The statistics' "closed_ball" at the oracle's scale: closed_ball_json(record.last) with rounds,
//! checks, witnesses_inserted, witnesses_rejected, current, seconds_refinement, and the decision's
//! output_equals_restricted_delaunay, only_restricted_delaunay, only_output, proves_homeomorphism
//! and exempt {count, by_kind: {kind: {reason: n}}, rule}.
nlohmann::json closed_ball_refinement_json(const ClosedBallRefinement& record, const PlStatusDecision& decision);

}  // namespace delmesh
