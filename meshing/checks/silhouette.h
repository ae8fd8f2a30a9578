#pragma once
//! \file silhouette.h
//! Silhouette(p) (§5.3, Lemma 4.14): V_p must not meet the silhouette J_{n_p}.

#include <optional>

#include "meshing/core/witness.h"
#include "meshing/voronoi/restricted_delaunay.h"

namespace delmesh {

//! The generic direction d′ ⟂ n_p used for p: the frame of n_p (solvers/query_geometry.h)
//! rotated by a seeded angle (attempt k > 0: the k-th alternative angle, attempt_seed()).
//! n_p = ∇E(p)/|∇E(p)|.
Vec3 silhouette_direction(const RestrictedDelaunay& restricted, VertexId p, const Vec3& n_p, int attempt = 0);

//! Lemma 4.14 allows any point of V_p ∩ J_{n_p} as the witness.  When the cell's gradient-cone
//! certificate (below) failed because it proved such a point (a zero of (E, ⟨∇E, n_p⟩) in V_p,
//! RestrictedDelaunay::cell_silhouette_point()), that point is returned and nothing is solved;
//! on a later attempt (attempt > 0, after it was rejected) the primitives below look for others.
//! Otherwise SilhouetteCritical(Σ, n_p, d′) over the clipped cell V_p: a point inside V_p (the
//! furthest from p; undecided regions are projected candidates) is returned.  Otherwise, for
//! every facet pq of V_p, SilhouettePlane(Σ, Π_pq, n_p) over the facet polygon: a point inside
//! the facet is returned.  Nothing if neither finds one.  Undecided regions whose projection fails or leaves
//! the face are unsettled (meshing/checks/detail/candidates.h); so are a zero gradient at p and an
//! empty clipped cell (numerical failures: p ∈ Σ is regular and interior to V_p).
//!
//! facets_clean: the caller asserts the §5.4 order — VorEdge, FacetContact, TopoDisk and
//! FacetCycle found nothing on the faces of V_p (Topology runs step (e) only then).  Then a facet
//! F = V_p ∩ V_q meets Σ only in open arcs ending on Voronoi edges of F (a closed curve would have
//! given a FacetCycle witness, and Σ does not reach ∂B), so a facet none of whose Voronoi edges
//! (the duals of the triangles pqr) meets Σ has F ∩ Σ = ∅ ⊇ F ∩ J_{n_p}, and SilhouettePlane is
//! skipped for it.  With facets_clean = false every facet is solved.
//!
//! Before each solve a gradient-cone certificate (solvers/gradient_cone.h, w = n_p) is tried on
//! the domain: when it proves ⟨∇E, n_p⟩ ≠ 0 on Σ ∩ V_p (resp. Σ ∩ F), that domain holds no point
//! of J_{n_p}, hence no root of SilhouetteCritical (resp. SilhouettePlane), and the solve is
//! skipped.  The cell's is RestrictedDelaunay::cell_certified(): a proof made over V_p when p was
//! inserted holds for the current V_p, which can only have shrunk since.  The certificate proves what an empty solver answer would say, so no root is lost;
//! only undecided regions (which it shows to hold no root) are not reported.
//!
//! attempt: which generic direction d′ SilhouetteCritical uses (silhouette_direction()).
CheckResult silhouette_witness(RestrictedDelaunay& restricted, VertexId p, bool facets_clean = false, int attempt = 0);

}  // namespace delmesh
