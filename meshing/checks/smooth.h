#pragma once
//! \file smooth.h
//! Smooth (§6.1): bounds the roughness g(pq) = π − dihedral angle of the edges of Tri S|Σ.

#include <optional>

#include "meshing/core/witness.h"
#include "meshing/voronoi/restricted_delaunay.h"

namespace delmesh {

//! The outward unit normal of the restricted triangle t: its geometric normal oriented to agree
//! with ∇E at the triangle's dual point on Σ (∇E points outward where E > 0 outside).
Vec3 outward_normal(RestrictedDelaunay& restricted, const TriangleKey& t);

//! If the edge pq of Tri S|Σ has exactly two restricted triangles and roughness (the angle
//! between their outward normals) > threshold (= 2β(λ)), the point of Σ on the dual Voronoi edges
//! of those two triangles that is furthest from p; otherwise nothing.
std::optional<Witness> smooth_witness(RestrictedDelaunay& restricted, const EdgeKey& pq, double threshold);

}  // namespace delmesh
