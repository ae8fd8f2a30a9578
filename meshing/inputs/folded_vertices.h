#pragma once
//! \file folded_vertices.h
//! Vertices of a triangle mesh that lie on the silhouette of every direction, and so keep the
//! Silhouette check of DelMesh (§5.3, on a piecewise-linear surface as meshing/inputs/mesh_oracle.h
//! defines it) from ever coming out clean.
//!
//! A vertex v is *folded* when the origin lies in the interior of the convex hull of the normal
//! vectors of the faces around v.  Then no run of DelMesh on the mesh can end complete.  Proof:
//! let N be those normals and n any direction.  If ⟨n_f, n⟩ ≥ 0 for every f ∈ N, the plane
//! ⟨x, n⟩ = 0 through the origin supports conv N, so the origin is on its boundary, not
//! interior; hence some face at v faces away from n (⟨n_f, n⟩ < 0), and, for −n, some face faces
//! n.  Going round v the sign changes, so v is on the silhouette J_n of the mesh for n (the edges
//! whose two faces face n opposite ways, and the vertices where that changes).  v lies in some
//! Voronoi cell V_p of every sample S, and with n = n_p the point v of J_{n_p} ∩ V_p is a
//! Silhouette witness, whatever S and n_p are.  Refinement near v therefore stops only at the
//! termination floor (--min-spacing), and the run ends uncertified.  (Gordan's theorem gives the
//! converse for the closed hull: when no direction is faced by every face at v, the origin is in
//! conv N; a vertex whose normals reach the origin only on the hull's boundary is not reported.)
//!
//! The test.  The origin is interior to conv N exactly when N spans ℝ³ and no direction n ≠ 0
//! has ⟨n_f, n⟩ ≥ 0 for every f: the cone C = {n : ⟨n_f, n⟩ ≥ 0 ∀f} is then {0}.  When N spans
//! ℝ³, C contains no line, so if C ≠ {0} it has an extreme ray, on which two linearly
//! independent constraints are tight: the ray is ±(n_i × n_j) for two normals with
//! n_i × n_j ≠ 0.  So v is folded iff N has rank 3 and each of the candidates ±(n_i × n_j) has some
//! f with ⟨n_f, ·⟩ < 0.  Before that, a direction m (the sum of the normals in doubles) with
//! ⟨n_f, m⟩ > 0 for every f lies in C and proves at once that v is not folded, which settles
//! every vertex of a smooth-looking mesh after k exact signs.
//!
//! Decided exactly: the face normals are the cross products (b − a) × (c − a) of the faces'
//! corners in exact arithmetic (CGAL::Exact_predicates_exact_constructions_kernel; a positive
//! multiple of the unit normal, which does not change the question), and every sign above is
//! exact; the answer never rests on rounding.

#include <cstddef>
#include <vector>

#include "meshing/core/surface_mesh.h"

namespace delmesh {

//! The folded vertices of `mesh` (see above), ascending by index.  Any mesh (border vertices and
//! isolated ones included: a vertex with fewer than four faces is never reported).  O(k_v) exact
//! signs for a vertex whose faces all face one direction, O(k_v³) at most otherwise, for k_v
//! faces at v.  Tests the command's limits (common/run_limits.h: RunLimits::current()) between
//! vertices and throws RunStopped when they have passed.
std::vector<SurfaceMesh::Vertex_index> folded_vertices(const SurfaceMesh& mesh);

}  // namespace delmesh
