#pragma once
//! \file topo_disk.h
//! TopoDisk(p) (§5.3, Lemmas 4.10 and 4.12): the restricted triangles at p must form a disk.

#include <optional>
#include <vector>

#include "meshing/core/witness.h"
#include "meshing/voronoi/restricted_delaunay.h"

namespace delmesh {

//! Whether the triangles T_p (each containing p) form a topological disk around p: T_p is
//! non-empty, every edge pq of T_p is shared by exactly two triangles of T_p, and the link
//! (the edges qr of the triangles pqr) is a single cycle.
bool is_topological_disk(const std::vector<TriangleKey>& star, VertexId p);

//! If the triangles of Tri S|Σ at p are not a topological disk, the point of Σ on the edges of
//! V_p furthest from p (then the others, furthest first); if no edge of V_p meets Σ, p itself as
//! unsettled (no_witness); otherwise nothing.
CheckResult topo_disk_witness(RestrictedDelaunay& restricted, VertexId p);

}  // namespace delmesh
