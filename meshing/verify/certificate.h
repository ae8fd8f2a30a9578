#pragma once
//! \file certificate.h
//! The topology certificate of a finished mesh: from a triangle soup and the surface
//! Σ = {E = 0} ⊂ interior(B) alone, with no state of the run that made the mesh, it decides
//! whether the soup is Tri S|Σ for the set S of its vertices and whether the five checks of §5.3
//! prove that Tri S|Σ is homeomorphic to Σ.
//!
//! **What a certified result rests on.**
//!  1. Theorem 2.1 (Edelsbrunner–Shah): if Vor S meets Σ generically and every Voronoi face
//!     meets Σ in the empty set or a closed ball of one dimension less (TBP), then the underlying
//!     space of Del S|Σ is homeomorphic to Σ.  S is any finite point set: the theorem does not
//!     ask the samples to lie on Σ.
//!  2. The argument of Lemma 5.3 and Corollary 5.1 with §5.1's perturbation Σ′: when VorEdge
//!     (Lemma 4.7) and FacetContact (Lemma 4.8) find nothing, Vor S meets Σ′ generically; when
//!     VorEdge, TopoDisk (Lemmas 4.10, 4.12), FacetCycle (Lemma 4.9) and Silhouette (Lemmas 4.13,
//!     4.14) find nothing either, every face satisfies TBP, so Tri S|Σ = Del S|Σ′ ≅ Σ.  The
//!     lemma's assumption that no component of Σ lies inside one Voronoi cell (the mesher gets it
//!     from its seeds) is implied here by Silhouette: a closed component M inside V_p contains
//!     points whose normal is orthogonal to n_p (the extremes of M in a direction ⟂ n_p), so
//!     J_{n_p} ∩ V_p ≠ ∅ and Silhouette(p) cannot come out clean.  The parts of §4 that use a
//!     sample p ∈ Σ (the distance bounds ‖p − x‖ ≥ λ f(p) of the witnesses, Lemma 5.1) concern
//!     the mesher's termination only; "no witness ⇒ TBP" does not use them, so vertices that lie
//!     near Σ but not on it (another program's output, or rounded coordinates) are certified on
//!     the same terms.  What the certificate then proves is the topology: the mesh is
//!     homeomorphic to Σ; it bounds no distance between the mesh and Σ.
//!  3. Every solver answer is certified (interval arithmetic, Krawczyk; the subdivision backend
//!     is always used, never homotopy continuation), relative to the floating-point Voronoi
//!     constructions of meshing/voronoi/voronoi_geometry.h, as for the mesher (docs/certificates.md,
//!     "What certified means").  Σ is first validated smooth and strictly inside B
//!     (input_validation.h).
//!
//! **Procedure.**  The referenced vertices of the soup, in index order, become S (ids 0, 1, …;
//! unreferenced points are left out; coincident points are one sample).  Del S is built, and on a
//! fresh RestrictedDelaunay (nothing cached before) the topology rows of the check registry
//! (meshing/checks/check_registry.h) run on every Voronoi face, edges first, then facets, then cells,
//! each face's rows in the registry's order: VorEdge on every Voronoi edge (each Delaunay
//! triangle's record also decides its membership in Tri S|Σ, with §5.1's rule), FacetContact on
//! every facet and FacetCycle on every facet FacetContact left clean (its precondition:
//! CheckInfo::after_clean_predecessors), TopoDisk and Silhouette on every cell.  A registered
//! topology row runs the same way.
//! Silhouette(p) skips the facets of V_p no Voronoi edge of which meets Σ only when the other
//! checks were clean on every face of V_p (silhouette.h).  Then Tri S|Σ is compared with the
//! soup's triangles as vertex sets.
//!
//! **Status.**
//!  - certified: every check of every face found no witness and left nothing unsettled;
//!  - violated: some check returned a *proved* witness, a point built from certified roots at
//!    which the condition the check verifies fails (two crossings of a Voronoi edge, a restricted
//!    star that is not a disk, a silhouette point in a cell, …).  The certificate's premises then
//!    do not hold; the mesh may still have Σ's topology, but nothing is proved;
//!  - undecided: no proved witness, but some region could not be decided: a candidate witness
//!    (the projection of an undecided solver region, or a witness relying on an unresolved
//!    crossing), an unsettled finding (witness.h: UnsettledReason), or an interruption.
//!
//! The generic directions of FacetCycle and Silhouette are seeded by CertificateOptions::seed and
//! the ids of S; another seed gives other directions and the same conclusion whenever both are
//! decided.

#include <array>
#include <atomic>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <ostream>
#include <vector>

#include <nlohmann/json.hpp>

#include "common/enum_names.h"
#include "meshing/core/surface_mesh.h"
#include "meshing/core/witness.h"
#include "symbolic/surface.h"

namespace delmesh {

enum class CertificateStatus { certified, violated, undecided };
constexpr auto enum_names(CertificateStatus) {
  return name_table<CertificateStatus>("CertificateStatus", {{CertificateStatus::certified, "certified"},
                                                             {CertificateStatus::violated, "violated"},
                                                             {CertificateStatus::undecided, "undecided"}});
}
inline std::ostream& operator<<(std::ostream& out, CertificateStatus status) { return write_enum(out, status); }

struct CertificateOptions {
  std::uint64_t seed = 1;  //!< seeds the generic directions of FacetCycle and Silhouette
  //! If given, the certificate stops at the first face after it becomes true (status
  //! undecided, `interrupted`); it is read between faces, so a signal handler may set it.
  const std::atomic<bool>* interrupt = nullptr;
  //! If given, the certificate stops at the first face after it has passed (status undecided,
  //! `time_limited`); its solves get it too (SurfaceOracle::set_run_controls), so one long solve
  //! ends there as well (its region undecided).
  std::optional<std::chrono::steady_clock::time_point> deadline;
};

//! A witness found by one check, on which Voronoi face, and whether it proves that the check's
//! condition fails (see the file comment).  `face` holds the soup indices of the dual Delaunay
//! simplex: one for a cell, two for a facet, three for an edge.
struct CertificateWitness {
  Witness witness;
  bool proved = false;
  std::vector<std::size_t> face;
};

//! Something a check left unsettled, on which Voronoi face (soup indices, as above).
struct CertificateUnsettled {
  Unsettled what;
  std::vector<std::size_t> face;
};

struct [[nodiscard]] Certificate {
  CertificateStatus status = CertificateStatus::undecided;
  bool interrupted = false;
  bool time_limited = false;  //!< CertificateOptions::deadline stopped it
  //! The soup's triangles are exactly Tri S|Σ (as vertex sets, each once, no coincident points).
  bool restricted_matches_mesh = false;

  std::size_t samples = 0;                //!< |S|: distinct referenced points
  std::size_t unreferenced_vertices = 0;  //!< soup points used by no triangle (left out of S)
  std::size_t coincident_vertices = 0;    //!< referenced points equal to an earlier one
  std::size_t voronoi_edges = 0, voronoi_facets = 0, voronoi_cells = 0;  //!< faces checked
  std::size_t faces_checked() const { return voronoi_edges + voronoi_facets + voronoi_cells; }

  std::size_t restricted_triangles = 0;           //!< |Tri S|Σ|
  std::size_t mesh_triangles = 0;                 //!< triangles of the soup
  std::size_t restricted_not_in_mesh = 0;         //!< triangles of Tri S|Σ the soup lacks
  std::size_t mesh_not_restricted = 0;            //!< soup triangles not in Tri S|Σ (or degenerate)
  std::size_t repeated_mesh_triangles = 0;        //!< soup triangles on the vertex set of an earlier one

  std::vector<CertificateWitness> witnesses;      //!< every witness, in the order found
  std::vector<CertificateUnsettled> unsettled;    //!< every unsettled finding, in the order found
  //! The largest first-order distance estimate |E(p)|/|∇E(p)| over S (not a bound; 0 on Σ).
  double max_vertex_distance_estimate = 0;

  double seconds = 0;                  //!< wall-clock time, validation included
  double seconds_validation = 0;
  std::vector<double> seconds_per_check;  //!< indexed by CheckKind (check_kind_count() entries)
  nlohmann::json solver;               //!< the oracle's statistics_json() of the certificate's solves
  std::uint64_t seed = 1;
};

//! Witnesses and unsettled findings listed one by one in to_json (all are counted).
inline constexpr std::size_t certificate_findings_listed = 10;

//! The certificate of the triangle soup (points, triangles) for Σ = {E = 0} in `box` (see the
//! file comment).  Throws InvalidInput if an index is out of range, a triangle repeats an index,
//! a referenced point is not finite, the soup has no triangle, or Σ fails validate_input (not
//! strictly inside the box, or not certified smooth).
Certificate certify_mesh(const std::vector<Point3>& points, const std::vector<std::array<std::size_t, 3>>& triangles,
                         const Surface& surface, const Box3& box, const CertificateOptions& options = {});

//! {status, restricted_matches_mesh, faces_checked, voronoi_faces {edges, facets, cells}, samples,
//!  unreferenced_vertices, coincident_vertices, restricted_triangles, mesh_triangles,
//!  restricted_not_in_mesh, mesh_not_restricted, repeated_mesh_triangles, witnesses {count, proved,
//!  by_check, listed: the first certificate_findings_listed, proved ones first, each {check, face,
//!  point, proved}}, unsettled {count, by_reason, listed: each {check, reason, face, location}},
//!  interrupted, time_limited, max_vertex_distance_estimate, seed, seconds, seconds_validation,
//!  seconds_per_check, solver}
nlohmann::json to_json(const Certificate& certificate);

}  // namespace delmesh
