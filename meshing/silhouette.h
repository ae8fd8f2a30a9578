#pragma once
//! \file silhouette.h
//! Silhouette(p) (§5.3, Lemma 4.14): V_p must not meet the silhouette J_{n_p}.

#include <optional>

#include "meshing/restricted_delaunay.h"
#include "meshing/witness.h"

namespace delmesh {

//! The generic direction d′ ⟂ n_p used for p: the frame of n_p (solvers/query_geometry.h)
//! rotated by a seeded angle.  n_p = ∇E(p)/|∇E(p)|.
Vec3 silhouette_direction(const RestrictedDelaunay& restricted, VertexId p, const Vec3& n_p);

//! SilhouetteCritical(Σ, n_p, d′) over the clipped cell V_p: a point inside V_p (the furthest
//! from p; undecided regions are projected candidates) is returned.  Otherwise, for every facet
//! pq of V_p, SilhouettePlane(Σ, Π_pq, n_p) over the facet polygon: a point inside the facet is
//! returned.  Nothing if neither finds one.
std::optional<Witness> silhouette_witness(RestrictedDelaunay& restricted, VertexId p);

}  // namespace delmesh
