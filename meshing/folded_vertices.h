#pragma once
//! \file folded_vertices.h
//! Vertices of a triangle mesh that lie on the silhouette of every direction, and so keep the
//! Silhouette check of DelMesh (§5.3, on a piecewise-linear surface as meshing/mesh_oracle.h
//! defines it) from ever coming out clean.
//!
//! A vertex v is *folded* when the origin lies in the interior of a tetrahedron spanned by the
//! normal vectors of four of the faces around v.  Then no run of DelMesh on the mesh can end
//! complete.  Proof: the origin is a combination Σ λ_f n_f = 0 of those four normals with every
//! λ_f > 0, and they span ℝ³, so for every direction n the numbers ⟨n_f, n⟩ are not all zero and
//! Σ λ_f ⟨n_f, n⟩ = 0: some face at v faces n (⟨n_f, n⟩ > 0) and another faces away
//! (⟨n_f, n⟩ < 0).  Going round v the sign changes, so v is on the silhouette J_n of the mesh for
//! n (the edges whose two faces face n opposite ways, and the vertices where that changes).
//! v lies in some Voronoi cell V_p of every sample S, and with n = n_p the point v of
//! J_{n_p} ∩ V_p is a Silhouette witness, whatever S and n_p are.  Refinement near v therefore
//! stops only at the termination floor (--min-spacing), and the run ends uncertified.
//! (The converse direction, for orientation: when no direction is faced by every face at v,
//! Gordan's theorem puts the origin in the convex hull of the normals; the test below reports
//! the vertices where it is interior to a tetrahedron of them, so a vertex whose normals meet
//! the origin only on a boundary, or do not span space, is not reported.  Every vertex reported
//! is folded.)
//!
//! Decided exactly: the face normals are the cross products (b − a) × (c − a) of the faces'
//! corners in exact arithmetic (CGAL::Exact_predicates_exact_constructions_kernel; a positive
//! multiple of the unit normal, which does not change the question), and the tetrahedra are
//! tested with exact orientations; the answer never rests on rounding.

#include <cstddef>
#include <vector>

#include "meshing/surface_mesh.h"

namespace delmesh {

//! The folded vertices of `mesh` (see above), ascending by index.  Any mesh (border vertices and
//! isolated ones included: a vertex with fewer than four faces is never reported).  O(Σ_v k_v⁴)
//! exact orientations for k_v faces at v, with an early exit per vertex.
std::vector<SurfaceMesh::Vertex_index> folded_vertices(const SurfaceMesh& mesh);

}  // namespace delmesh
