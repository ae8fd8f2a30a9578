#pragma once
//! \file vor_edge.h
//! VorEdge(e) (§5.3, Lemma 4.7): the generic-intersection and TBP check of one Voronoi edge.

#include <optional>

#include "meshing/core/witness.h"
#include "meshing/voronoi/restricted_delaunay.h"

namespace delmesh {

//! For the Voronoi edge e dual to the Delaunay triangle t (its intersections with Σ from
//! RestrictedDelaunay::edge_record):
//! - if the support line meets Σ tangentially at a point of e (an undecided singular region of
//!   SurfaceLine, projected onto Σ — or any other undecided region, as a candidate), returns it;
//! - if |e ∩ Σ| ≥ 2, returns the point of e ∩ Σ furthest from p;
//! - otherwise nothing.
//! p is the smallest-id vertex of t (every vertex of t is equidistant from every point of e).
//! The witnesses are listed in that order of preference (candidates, then crossings, each
//! furthest from p first).  Undecided regions the record could not place are not judged here:
//! they are RestrictedDelaunay's unresolved regions, judged on the final Tri S|Σ.
CheckResult vor_edge_witness(RestrictedDelaunay& restricted, const TriangleKey& t);

}  // namespace delmesh
