#pragma once
//! \file smooth.h
//! Smooth (§6.1): bounds the roughness g(pq) = π − dihedral angle of the edges of Tri S|Σ.
//!
//! Smooth on a piecewise-linear input with sharp features.  The bound g(pq) ≤ 2β(λ) rests on Σ
//! being C² near pq; across a crease of a triangle mesh the normal jumps by the crease's angle
//! at every sample spacing, so no refinement makes it hold there.  When the oracle is a
//! MeshOracle with feature edges (meshing/inputs/mesh_oracle.h: set_feature_edges, from the run's
//! feature angle), an edge pq whose roughness exceeds the bound and whose Voronoi facet V_p ∩ V_q
//! meets a feature edge (FeatureEdges::facet_meets_feature_edge, meshing/inputs/sharp_features.h,
//! exact) is not refined: smooth_check() reports it as an unsettled finding (check smooth,
//! reason no_witness, at smooth_witness()'s point) instead of a witness.  Like every unsettled
//! finding it keeps the run from ending complete, unless the status rule of a PL run exempts it
//! (meshing/driver/closed_ball_refinement.h, decide_pl_status: only when the closed-ball property
//! holds on the final samples and Tri S|Σ = Del S|Σ).  Any other oracle, or a MeshOracle without
//! feature edges, has no exempt edge: Smooth is the paper's.

#include <optional>

#include "meshing/core/witness.h"
#include "meshing/voronoi/restricted_delaunay.h"

namespace delmesh {

//! The outward unit normal of the restricted triangle t: its geometric normal oriented to agree
//! with ∇E at the triangle's dual point on Σ (∇E points outward where E > 0 outside).
Vec3 outward_normal(RestrictedDelaunay& restricted, const TriangleKey& t);

//! If the edge pq of Tri S|Σ has exactly two restricted triangles and roughness (the angle
//! between their outward normals) > threshold (= 2β(λ)), the point of Σ on the dual Voronoi edges
//! of those two triangles that is furthest from p; otherwise nothing.  (The finding itself,
//! whether or not the edge is exempt.)
std::optional<Witness> smooth_witness(RestrictedDelaunay& restricted, const EdgeKey& pq, double threshold);

//! Whether pq is a crease edge for Smooth (file comment): the oracle is a MeshOracle with feature
//! edges and the Voronoi facet of pq in the current Del S meets one of them.  Precondition: pq is
//! an edge of Del S.
bool smooth_exempt_edge(RestrictedDelaunay& restricted, const EdgeKey& pq);

//! The Smooth row on a triangle t of Del S: nothing unless t is restricted; else, over its edges
//! in the order (t0 t1), (t0 t2), (t1 t2), the smooth_witness() of the first edge that is not a
//! crease edge, if one has a finding; otherwise each finding on a crease edge as an unsettled
//! finding (smooth, no_witness, at its point).  Without crease edges this is the paper's check:
//! the first edge's witness.
CheckResult smooth_check(RestrictedDelaunay& restricted, const TriangleKey& t, double threshold);

}  // namespace delmesh
